// gltf_read.hpp — read back glTF / GLB files written by the exporter (tinygltf parse, accessor
// decoding written here, node transforms applied in double).
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "knit/polylines.hpp"

#include "export/test_curves.hpp"

namespace knit::test {

inline tinygltf::Model loadGltf(const std::string& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool glb = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
    const bool ok = glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                        : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    EXPECT_TRUE(ok) << path << ": " << err << " " << warn;
    return model;
}

inline size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        default: return 4;
    }
}

inline int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

// All values of an accessor as doubles (count x components), normalized integers mapped to
// [-1, 1] / [0, 1] as the glTF spec defines, raw integers kept as integers.
inline std::vector<double> readAccessor(const tinygltf::Model& m, int index) {
    const tinygltf::Accessor& a = m.accessors.at(size_t(index));
    const int nc = componentCount(a.type);
    std::vector<double> out(a.count * size_t(nc), 0.0);
    if (a.bufferView < 0) return out;
    const tinygltf::BufferView& v = m.bufferViews.at(size_t(a.bufferView));
    const tinygltf::Buffer& b = m.buffers.at(size_t(v.buffer));
    const size_t cb = componentBytes(a.componentType);
    const size_t stride = v.byteStride ? v.byteStride : cb * size_t(nc);
    const unsigned char* base = b.data.data() + v.byteOffset + a.byteOffset;
    for (size_t i = 0; i < a.count; ++i) {
        for (int k = 0; k < nc; ++k) {
            const unsigned char* p = base + i * stride + size_t(k) * cb;
            double x = 0;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); x = f; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); x = u; break; }
                case TINYGLTF_COMPONENT_TYPE_SHORT: {
                    int16_t s; std::memcpy(&s, p, 2);
                    x = a.normalized ? std::max(double(s) / 32767.0, -1.0) : double(s);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    uint16_t s; std::memcpy(&s, p, 2);
                    x = a.normalized ? double(s) / 65535.0 : double(s);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_BYTE: {
                    int8_t s; std::memcpy(&s, p, 1);
                    x = a.normalized ? std::max(double(s) / 127.0, -1.0) : double(s);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: x = a.normalized ? double(*p) / 255.0 : double(*p); break;
            }
            out[i * size_t(nc) + size_t(k)] = x;
        }
    }
    return out;
}

inline glm::dmat4 localMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];
        return m;
    }
    glm::dmat4 m(1.0);
    if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4)
        m = m * glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
    if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

// Every mesh instance of the default scene with its world matrix (depth-first).
struct MeshInstance {
    int mesh;
    glm::dmat4 world;
    int node;
};

inline void collectInstances(const tinygltf::Model& m, int node, const glm::dmat4& parent, std::vector<MeshInstance>& out) {
    const tinygltf::Node& n = m.nodes.at(size_t(node));
    const glm::dmat4 world = parent * localMatrix(n);
    if (n.mesh >= 0) out.push_back({n.mesh, world, node});
    for (int c : n.children) collectInstances(m, c, world, out);
}

inline std::vector<MeshInstance> meshInstances(const tinygltf::Model& m) {
    std::vector<MeshInstance> out;
    const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
    for (int root : m.scenes.at(size_t(s)).nodes) collectInstances(m, root, glm::dmat4(1.0), out);
    return out;
}

// World-space positions of one primitive's POSITION accessor.
inline std::vector<glm::dvec3> worldPositions(const tinygltf::Model& m, const tinygltf::Primitive& p, const glm::dmat4& world) {
    const std::vector<double> v = readAccessor(m, p.attributes.at("POSITION"));
    std::vector<glm::dvec3> out(v.size() / 3);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = glm::dvec3(world * glm::dvec4(v[3 * i], v[3 * i + 1], v[3 * i + 2], 1.0));
    return out;
}

// Largest distance between the curves of a curve export (one LINE_STRIP primitive per curve, in
// file order; a closed curve repeats its first point) and the exported curves `c`. Adds a test
// failure when the curve or point counts differ.
inline double worstCurveDeviation(const tinygltf::Model& m, const Polylines& c) {
    double worst = 0;
    size_t curve = 0;
    for (const MeshInstance& inst : meshInstances(m)) {
        for (const tinygltf::Primitive& p : m.meshes[size_t(inst.mesh)].primitives) {
            if (curve >= c.curveCount()) {
                ADD_FAILURE() << "more curves in the file than exported (" << c.curveCount() << ")";
                return worst;
            }
            const std::vector<glm::dvec3> pos = worldPositions(m, p, inst.world);
            const size_t n = c.size(curve);
            EXPECT_EQ(pos.size(), n + (c.isClosed(curve) ? 1 : 0)) << "curve " << curve;
            for (size_t i = 0; i < n && i < pos.size(); ++i)
                worst = std::max(worst, glm::length(pos[i] - c.points[c.begin(curve) + i]));
            if (c.isClosed(curve) && pos.size() == n + 1) EXPECT_EQ(pos.front(), pos.back()) << "curve " << curve;
            ++curve;
        }
    }
    EXPECT_EQ(curve, c.curveCount());
    return worst;
}

// A container-level reader independent of tinygltf (tinygltf 2.7 without Draco support rejects
// the bufferView-less index accessors that KHR_draco_mesh_compression files use): the JSON
// document and every buffer's bytes (GLB BIN chunk or external .bin by URI).
struct RawGltf {
    nlohmann::json doc;
    std::vector<std::vector<unsigned char>> buffers;
};

inline std::string uriDecode(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size()) {
            out.push_back(char(std::stoi(s.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(s[i]);
        }
    }
    return out;
}

inline RawGltf loadRawGltf(const std::string& path) {
    RawGltf g;
    const std::vector<unsigned char> bytes = readBytes(path);
    std::vector<unsigned char> bin;
    if (bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        uint32_t version, length, jsonLength, jsonType;
        std::memcpy(&version, &bytes[4], 4);
        std::memcpy(&length, &bytes[8], 4);
        std::memcpy(&jsonLength, &bytes[12], 4);
        std::memcpy(&jsonType, &bytes[16], 4);
        EXPECT_EQ(version, 2u);
        EXPECT_EQ(length, bytes.size());
        EXPECT_EQ(jsonType, 0x4E4F534Au);
        EXPECT_EQ(jsonLength % 4, 0u);
        g.doc = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
        const size_t at = 20 + jsonLength;
        if (at + 8 <= bytes.size()) {
            uint32_t binLength, binType;
            std::memcpy(&binLength, &bytes[at], 4);
            std::memcpy(&binType, &bytes[at + 4], 4);
            EXPECT_EQ(binType, 0x004E4942u);
            EXPECT_EQ(binLength % 4, 0u);
            bin.assign(bytes.begin() + long(at + 8), bytes.begin() + long(at + 8 + binLength));
        }
    } else {
        g.doc = nlohmann::json::parse(bytes.begin(), bytes.end());
    }
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    for (const auto& b : g.doc.value("buffers", nlohmann::json::array())) {
        if (b.contains("uri")) g.buffers.push_back(readBytes((folder / uriDecode(b["uri"].get<std::string>())).string()));
        else g.buffers.push_back(bin);
        EXPECT_GE(g.buffers.back().size(), b["byteLength"].get<size_t>());
    }
    return g;
}

}  // namespace knit::test
