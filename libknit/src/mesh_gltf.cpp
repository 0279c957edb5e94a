// mesh_gltf.cpp — glTF 2.0 base meshes (.gltf / .glb), read with nlohmann::json.
//
// Why not tinygltf's loader: Debian's libdraco exports its own, older copy of tinygltf's
// symbols, so in any process that loads both (the `knit` CLI, the exporters) a call to
// tinygltf::TinyGLTF::Load* may land in Draco's copy, built for a different class layout: it
// crashed (free() of an invalid pointer) on every glTF file. The part of glTF a base mesh
// needs (GLB container, buffers, views, accessors, meshes, the node tree) is small, and reading
// it here also lets every range be checked before it is touched.
//
// What is read:
//  * The mesh instances of the default scene (scene 0 when none is set; every mesh once,
//    untransformed, when the file has no scenes), each with its node's world transform (matrix
//    or translation * rotation * scale, composed in double) applied to POSITION; a mirroring
//    transform (negative determinant) reverses the triangles' winding, as glTF specifies. Nodes
//    form a tree, walked without recursion: a node reached twice (a cycle, or two parents) is an
//    error. Instancing can multiply a small file: more than MeshLoadOptions::maxElements
//    vertices or triangles in total are refused.
//  * TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (strips and fans are unrolled;
//    triangles with a repeated index, e.g. strip restarts, are skipped). POINTS and LINES
//    primitives are not surfaces and are ignored; a file without any triangle is an error.
//  * POSITION (float, or the integer types of KHR_mesh_quantization) and TEXCOORD_0 (float, or
//    normalized unsigned byte / short) are required; indices are optional (u8 / u16 / u32).
//  * UV convention: glTF puts the texture origin at the top-left corner (v down), libknit like
//    OBJ at the bottom-left, so v is flipped: uv = (u, 1 - v). The same asset exported as OBJ
//    and as glTF gets the same knit.
//  * Vertices are welded by exact position like the other formats (glTF duplicates vertices at
//    UV seams), so normals and yarn welding see one 3D topology.
//  * Buffers: the GLB BIN chunk, base64 `data:` URIs, or files given by relative URIs
//    (percent-decoded), read as regular files relative to the glTF's folder (their first
//    byteLength bytes); only buffers the mesh needs are read (never images). Absolute paths and
//    other schemes are refused.
//  * Refused with knit::Error naming the element: KHR_draco_mesh_compression primitives, sparse
//    accessors, accessors without data, out-of-range indices, accessor or buffer-view ranges
//    outside their buffer, non-finite values, malformed JSON or GLB.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "mesh_weld.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <cctype>
#include <limits>
#include <map>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

namespace knit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kTriangles = 4, kTriangleStrip = 5, kTriangleFan = 6;

[[noreturn]] void fail(const std::string& file, const std::string& what) { throw Error(file + ": " + what); }

int componentBytes(int type) {
    switch (type) {
        case kByte:
        case kUnsignedByte: return 1;
        case kShort:
        case kUnsignedShort: return 2;
        case kUnsignedInt:
        case kFloat: return 4;
        default: return 0;
    }
}

int componentsOf(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4" || type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}

// A checked view of one accessor's elements.
struct AccessorData {
    const unsigned char* base = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;

    // Component k of element i as a double (normalized integers mapped as the glTF spec says).
    double get(size_t i, int k) const {
        const unsigned char* p = base + i * stride + size_t(k) * size_t(componentBytes(componentType));
        switch (componentType) {
            case kFloat: { float f; std::memcpy(&f, p, 4); return f; }
            case kUnsignedByte: return normalized ? p[0] / 255.0 : p[0];
            case kByte: {
                const double v = double(int8_t(p[0]));
                return normalized ? std::max(v / 127.0, -1.0) : v;
            }
            case kUnsignedShort: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
            case kShort: {
                int16_t v;
                std::memcpy(&v, p, 2);
                return normalized ? std::max(v / 32767.0, -1.0) : double(v);
            }
            case kUnsignedInt: { uint32_t v; std::memcpy(&v, p, 4); return double(v); }
            default: return 0.0;
        }
    }
};

std::optional<std::vector<unsigned char>> decodeBase64(const std::string& s, size_t from) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+' || c == '-') return 62;
        if (c == '/' || c == '_') return 63;
        return -1;
    };
    std::vector<unsigned char> out;
    out.reserve((s.size() - from) / 4 * 3);
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = from; i < s.size(); ++i) {
        if (s[i] == '=') break;
        const int v = value(s[i]);
        if (v < 0) return std::nullopt;
        acc = (acc << 6) | uint32_t(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(uint8_t(acc >> bits));
        }
    }
    return out;
}

std::string percentDecode(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(uint8_t(s[i + 1])) && std::isxdigit(uint8_t(s[i + 2]))) {
            out.push_back(char(std::stoi(s.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(s[i]);
        }
    }
    return out;
}

class GltfMeshReader {
public:
    GltfMeshReader(const std::string& bytes, const std::string& name, const std::string& baseDir, uint64_t maxElements)
        : name_(name), baseDir_(baseDir), maxElements_(maxElements) {
        parseContainer(bytes);
    }

    BaseMesh read(const MeshLoadOptions& options) {
        // Step 1: mesh instances with their world transforms.
        const json& scenes = member(doc_, "scenes", json::value_t::array, "the document");
        if (!scenes.empty()) {
            const size_t s = index(doc_, "scene", "the document").value_or(0);
            if (s >= scenes.size()) fail(name_, "scene " + std::to_string(s) + " does not exist");
            const json& roots = member(scenes[s], "nodes", json::value_t::array, "scenes[" + std::to_string(s) + "]");
            std::vector<char> reached(member(doc_, "nodes", json::value_t::array, "the document").size(), 0);
            for (const json& root : roots) visit(asIndex(root, "scenes[" + std::to_string(s) + "].nodes"), reached);
        } else {
            const size_t meshes = member(doc_, "meshes", json::value_t::array, "the document").size();
            for (size_t k = 0; k < meshes; ++k) addMesh(k, glm::dmat4(1.0));
        }
        if (faceStart_.size() == 1) fail(name_, "no triangle primitives in the default scene (libknit needs a triangle mesh)");
        // Step 2: weld into a BaseMesh.
        BaseMesh mesh = detail::weldPolygons(name_, points_, faceStart_, faceVerts_,
                                             [&](uint32_t c) { return uvs_[size_t(faceVerts_[c])]; }, options);
        validateMesh(mesh);
        return mesh;
    }

private:
    // ---- container and JSON helpers ----------------------------------------------------------------
    void parseContainer(const std::string& bytes) {
        std::string text = bytes;
        if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
            // GLB: 12-byte header, a JSON chunk, optionally a BIN chunk.
            auto u32 = [&](size_t at) {
                uint32_t v;
                std::memcpy(&v, bytes.data() + at, 4);
                return v;
            };
            if (bytes.size() < 20) fail(name_, "truncated GLB header");
            if (u32(4) != 2) fail(name_, "GLB version " + std::to_string(u32(4)) + " (only glTF 2.0 is read)");
            const size_t total = u32(8);
            if (total > bytes.size()) fail(name_, "truncated GLB: the header says " + std::to_string(total) + " bytes, the file has " + std::to_string(bytes.size()));
            const size_t jsonLength = u32(12);
            if (u32(16) != 0x4E4F534A) fail(name_, "the first GLB chunk is not JSON");
            if (jsonLength > total - 20) fail(name_, "the GLB JSON chunk runs past the end of the file");
            text = bytes.substr(20, jsonLength);
            const size_t next = 20 + (jsonLength + 3) / 4 * 4;
            if (next + 8 <= total && u32(next + 4) == 0x004E4942) {
                const size_t binLength = u32(next);
                if (binLength > total - next - 8) fail(name_, "the GLB BIN chunk runs past the end of the file");
                glbBin_.emplace(bytes.begin() + std::ptrdiff_t(next + 8), bytes.begin() + std::ptrdiff_t(next + 8 + binLength));
            }
        }
        try {
            doc_ = json::parse(text);
        } catch (const json::exception& e) {
            fail(name_, std::string("not valid glTF JSON: ") + e.what());
        }
        if (!doc_.is_object()) fail(name_, "not valid glTF JSON: the document is not an object");
        const json& asset = member(doc_, "asset", json::value_t::object, "the document");
        const json* version = asset.contains("version") ? &asset["version"] : nullptr;
        if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0)
            fail(name_, "asset.version must be \"2.x\" (only glTF 2.0 is read)");
    }

    // obj[key] when present (of `type`), else an empty value of that type.
    const json& member(const json& obj, const char* key, json::value_t type, const std::string& where) const {
        static const json emptyArray = json::array(), emptyObject = json::object();
        if (obj.is_object() && obj.contains(key)) {
            const json& v = obj[key];
            if (v.type() != type) fail(name_, where + "." + key + " has the wrong JSON type");
            return v;
        }
        return type == json::value_t::array ? emptyArray : emptyObject;
    }
    size_t asIndex(const json& v, const std::string& where) const {
        if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
            fail(name_, where + " must be a non-negative integer");
        return v.get<size_t>();
    }
    std::optional<size_t> index(const json& obj, const char* key, const std::string& where) const {
        if (!obj.is_object() || !obj.contains(key)) return std::nullopt;
        return asIndex(obj[key], where + "." + key);
    }
    const json& element(const char* array, size_t i, const std::string& what) const {
        const json& a = member(doc_, array, json::value_t::array, "the document");
        if (i >= a.size() || !a[i].is_object())
            fail(name_, what + ": " + array + "[" + std::to_string(i) + "] does not exist");
        return a[i];
    }
    std::vector<double> numbers(const json& obj, const char* key, size_t n, const std::string& where) const {
        if (!obj.contains(key)) return {};
        const json& v = obj[key];
        if (!v.is_array() || v.size() != n) fail(name_, where + "." + key + " must be an array of " + std::to_string(n) + " numbers");
        std::vector<double> out;
        for (const json& x : v) {
            if (!x.is_number()) fail(name_, where + "." + key + " must be an array of " + std::to_string(n) + " numbers");
            out.push_back(x.get<double>());
            if (!std::isfinite(out.back())) fail(name_, where + "." + key + " is not finite");
        }
        return out;
    }

    // ---- buffers and accessors ---------------------------------------------------------------------
    const std::vector<unsigned char>& buffer(size_t i, const std::string& what) {
        if (auto it = buffers_.find(i); it != buffers_.end()) return it->second;
        const json& b = element("buffers", i, what);
        const std::string where = "buffers[" + std::to_string(i) + "]";
        const size_t length = index(b, "byteLength", where).value_or(0);
        std::vector<unsigned char> data;
        if (!b.contains("uri")) {
            if (i != 0 || !glbBin_) fail(name_, where + " has no uri and there is no GLB BIN chunk");
            data = *glbBin_;
        } else {
            if (!b["uri"].is_string()) fail(name_, where + ".uri must be a string");
            const std::string uri = b["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) {
                const size_t comma = uri.find(',');
                if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
                    fail(name_, where + ": only base64 data URIs are read");
                auto decoded = decodeBase64(uri, comma + 1);
                if (!decoded) fail(name_, where + ": malformed base64 data URI");
                data = std::move(*decoded);
            } else {
                data = externalFile(percentDecode(uri), where, length);
            }
        }
        if (data.size() < length)
            fail(name_, where + " has " + std::to_string(data.size()) + " bytes, less than its byteLength " + std::to_string(length));
        data.resize(length);
        return buffers_.emplace(i, std::move(data)).first->second;
    }

    // The first `length` bytes of an external file (its size is checked first).
    std::vector<unsigned char> externalFile(const std::string& uri, const std::string& where, size_t length) const {
        if (baseDir_.empty()) fail(name_, where + ": external file '" + uri + "' not allowed here (parsed from memory)");
        if (uri.empty() || uri.find(':') != std::string::npos || fs::path(uri).is_absolute())
            fail(name_, where + ": uri '" + uri + "' is not a relative file path");
        const fs::path path = fs::path(baseDir_) / uri;
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) fail(name_, where + ": '" + path.string() + "' is not a readable file");
        const uintmax_t size = fs::file_size(path, ec);
        if (ec || size < length)
            fail(name_, where + ": '" + path.string() + "' has " + std::to_string(ec ? 0 : size) +
                            " bytes, less than the buffer's byteLength " + std::to_string(length));
        std::vector<unsigned char> data(length);
        std::ifstream in(path, std::ios::binary);
        if (!in.read(reinterpret_cast<char*>(data.data()), std::streamsize(length)))
            fail(name_, where + ": cannot read '" + path.string() + "'");
        return data;
    }

    // Checked view of accessor `i` (`what` names its use in messages).
    AccessorData accessor(size_t i, const std::string& what) {
        const json& a = element("accessors", i, what);
        const std::string where = "accessors[" + std::to_string(i) + "]";
        if (a.contains("sparse")) fail(name_, what + ": sparse accessors are not supported");
        const std::optional<size_t> viewIndex = index(a, "bufferView", where);
        if (!viewIndex) fail(name_, what + ": " + where + " has no data (no bufferView)");
        const json& v = element("bufferViews", *viewIndex, what);
        const std::string vWhere = "bufferViews[" + std::to_string(*viewIndex) + "]";
        const std::optional<size_t> bufferIndex = index(v, "buffer", vWhere);
        if (!bufferIndex) fail(name_, what + ": " + vWhere + " has no buffer");
        const std::vector<unsigned char>& data = buffer(*bufferIndex, what);
        AccessorData d;
        d.componentType = int(index(a, "componentType", where).value_or(0));
        if (!a.contains("type") || !a["type"].is_string()) fail(name_, what + ": " + where + " has no type");
        d.components = componentsOf(a["type"].get<std::string>());
        d.normalized = a.contains("normalized") && a["normalized"].is_boolean() && a["normalized"].get<bool>();
        d.count = index(a, "count", where).value_or(0);
        const int cb = componentBytes(d.componentType);
        if (cb == 0 || d.components == 0) fail(name_, what + ": " + where + " has an unknown component type or type");
        const size_t elementSize = size_t(cb) * size_t(d.components);
        const size_t viewOffset = index(v, "byteOffset", vWhere).value_or(0);
        const size_t viewLength = index(v, "byteLength", vWhere).value_or(0);
        d.stride = index(v, "byteStride", vWhere).value_or(0);
        if (d.stride == 0) d.stride = elementSize;
        if (d.stride < elementSize) fail(name_, what + ": " + vWhere + " has a byteStride below the element size");
        if (viewOffset > data.size() || viewLength > data.size() - viewOffset)
            fail(name_, what + ": " + vWhere + " lies outside its buffer");
        const size_t offset = index(a, "byteOffset", where).value_or(0);
        if (d.count > 0 && (offset > viewLength || elementSize > viewLength - offset ||
                            (d.count - 1) > (viewLength - offset - elementSize) / d.stride))
            fail(name_, what + ": " + where + " (" + std::to_string(d.count) + " elements) reaches past the end of " + vWhere);
        d.base = data.data() + viewOffset + offset;
        return d;
    }

    // ---- scene graph and primitives -------------------------------------------------------------------
    // Depth-first over the node tree from `root`, with an explicit stack (deep chains are fine).
    void visit(size_t root, std::vector<char>& reached) {
        std::vector<std::pair<size_t, glm::dmat4>> stack{{root, glm::dmat4(1.0)}};
        while (!stack.empty()) {
            const auto [i, parent] = stack.back();
            stack.pop_back();
            const json& n = element("nodes", i, "the scene");
            if (reached[i]) fail(name_, "node " + std::to_string(i) + " is reached twice (glTF nodes must form a tree)");
            reached[i] = 1;
            const std::string where = "nodes[" + std::to_string(i) + "]";
            const glm::dmat4 world = parent * localTransform(n, i);
            if (const auto mesh = index(n, "mesh", where)) addMesh(*mesh, world);
            const json& children = member(n, "children", json::value_t::array, where);
            for (auto it = children.rbegin(); it != children.rend(); ++it)
                stack.emplace_back(asIndex(*it, where + ".children"), world);  // reversed: visited in order
        }
    }

    glm::dmat4 localTransform(const json& n, size_t i) const {
        const std::string where = "nodes[" + std::to_string(i) + "]";
        glm::dmat4 m(1.0);
        if (const std::vector<double> v = numbers(n, "matrix", 16, where); !v.empty()) {
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = v[size_t(4 * c + r)];  // column-major
            return m;
        }
        if (const std::vector<double> t = numbers(n, "translation", 3, where); !t.empty())
            m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
        if (const std::vector<double> r = numbers(n, "rotation", 4, where); !r.empty()) {
            const glm::dquat q(r[3], r[0], r[1], r[2]);  // stored (x, y, z, w)
            const double len = glm::length(q);
            if (!(len > 0)) fail(name_, where + ".rotation is not a rotation (zero quaternion)");
            m = m * glm::mat4_cast(q / len);
        }
        if (const std::vector<double> s = numbers(n, "scale", 3, where); !s.empty())
            m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
        return m;
    }

    void addMesh(size_t meshIndex, const glm::dmat4& world) {
        const json& mesh = element("meshes", meshIndex, "a node");
        const std::string meshWhere = "meshes[" + std::to_string(meshIndex) + "]";
        const std::string meshName = mesh.contains("name") && mesh["name"].is_string() ? mesh["name"].get<std::string>() : "";
        const json& prims = member(mesh, "primitives", json::value_t::array, meshWhere);
        for (size_t p = 0; p < prims.size(); ++p) {
            const json& prim = prims[p];
            const std::string what = "mesh " + std::to_string(meshIndex) + (meshName.empty() ? "" : " ('" + meshName + "')") +
                                     " primitive " + std::to_string(p);
            if (!prim.is_object()) fail(name_, what + " is not an object");
            const size_t mode = index(prim, "mode", what).value_or(kTriangles);
            if (mode != kTriangles && mode != kTriangleStrip && mode != kTriangleFan) continue;  // not a surface
            if (member(prim, "extensions", json::value_t::object, what).contains("KHR_draco_mesh_compression"))
                fail(name_, what + " is Draco-compressed (KHR_draco_mesh_compression), which cannot be read here; "
                                   "export the base mesh without Draco");
            const json& attributes = member(prim, "attributes", json::value_t::object, what);
            const std::optional<size_t> pos = index(attributes, "POSITION", what + ".attributes");
            if (!pos) fail(name_, what + " has no POSITION");
            const std::optional<size_t> tex = index(attributes, "TEXCOORD_0", what + ".attributes");
            if (!tex) fail(name_, what + " has no TEXCOORD_0 (libknit needs UVs)");
            const AccessorData P = accessor(*pos, what + " POSITION");
            const AccessorData T = accessor(*tex, what + " TEXCOORD_0");
            if (P.components != 3) fail(name_, what + ": POSITION is not VEC3");
            if (T.components != 2) fail(name_, what + ": TEXCOORD_0 is not VEC2");
            if (T.count != P.count)
                fail(name_, what + ": TEXCOORD_0 has " + std::to_string(T.count) + " elements, POSITION " + std::to_string(P.count));
            if (points_.size() + P.count > std::min<uint64_t>(maxElements_, uint64_t(std::numeric_limits<int>::max())))
                fail(name_, "more than " + std::to_string(maxElements_) + " vertices in the scene (MeshLoadOptions::maxElements)");
            // Vertices: world positions in double, v flipped (glTF's texture origin is top-left).
            const size_t first = points_.size();
            for (size_t i = 0; i < P.count; ++i) {
                const glm::dvec4 x = world * glm::dvec4(P.get(i, 0), P.get(i, 1), P.get(i, 2), 1.0);
                const glm::dvec2 uv(T.get(i, 0), 1.0 - T.get(i, 1));
                if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
                    fail(name_, what + ": vertex " + std::to_string(i) + " has a non-finite position");
                if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                    fail(name_, what + ": vertex " + std::to_string(i) + " has a non-finite TEXCOORD_0");
                points_.emplace_back(x);
                uvs_.push_back(uv);
            }
            // Indices (or 0..count-1), then triangles by mode.
            std::vector<uint32_t> idx;
            const std::optional<size_t> indices = index(prim, "indices", what);
            if (indices) {
                const AccessorData I = accessor(*indices, what + " indices");
                if (I.components != 1 || (I.componentType != kUnsignedByte && I.componentType != kUnsignedShort &&
                                          I.componentType != kUnsignedInt))
                    fail(name_, what + ": indices must be unsigned byte, short or int scalars");
                idx.resize(I.count);
                for (size_t i = 0; i < I.count; ++i) {
                    const double v = I.get(i, 0);
                    if (v >= double(P.count))
                        fail(name_, what + ": index " + std::to_string(i) + " is " + std::to_string(uint64_t(v)) +
                                        " but there are " + std::to_string(P.count) + " vertices");
                    idx[i] = uint32_t(v);
                }
            } else {
                idx.resize(P.count);
                for (size_t i = 0; i < P.count; ++i) idx[i] = uint32_t(i);
            }
            // A mirroring world transform turns the winding around (glTF: det < 0 reverses it).
            const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;
            auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
                if (a == b || b == c || a == c) return;  // degenerate (strip restart)
                if (mirrored) std::swap(b, c);
                for (uint32_t v : {a, b, c}) faceVerts_.push_back(int(first + v));
                faceStart_.push_back(uint32_t(faceVerts_.size()));
            };
            const size_t triangles = mode == kTriangles ? idx.size() / 3 : (idx.size() >= 3 ? idx.size() - 2 : 0);
            if (faceStart_.size() - 1 + triangles > maxElements_)
                fail(name_, "more than " + std::to_string(maxElements_) + " triangles in the scene (MeshLoadOptions::maxElements)");
            if (mode == kTriangles) {
                if (idx.size() % 3 != 0)
                    fail(name_, what + ": " + std::to_string(idx.size()) + (indices ? " indices" : " vertices") +
                                    " do not make whole triangles");
                for (size_t i = 0; i + 3 <= idx.size(); i += 3) triangle(idx[i], idx[i + 1], idx[i + 2]);
            } else if (mode == kTriangleStrip) {
                for (size_t i = 0; i + 2 < idx.size(); ++i)
                    i % 2 == 0 ? triangle(idx[i], idx[i + 1], idx[i + 2]) : triangle(idx[i + 1], idx[i], idx[i + 2]);
            } else {
                for (size_t i = 1; i + 1 < idx.size(); ++i) triangle(idx[0], idx[i], idx[i + 1]);
            }
        }
    }

    std::string name_, baseDir_;
    uint64_t maxElements_;
    json doc_;
    std::optional<std::vector<unsigned char>> glbBin_;
    std::map<size_t, std::vector<unsigned char>> buffers_;  // read on first use
    std::vector<glm::dvec3> points_;
    std::vector<glm::dvec2> uvs_;
    std::vector<uint32_t> faceStart_{0};
    std::vector<int> faceVerts_;
};

}  // namespace

BaseMesh parseGltfMesh(const std::string& bytes, const std::string& name, const std::string& baseDir,
                       const MeshLoadOptions& options) {
    return GltfMeshReader(bytes, name, baseDir, options.maxElements).read(options);
}

BaseMesh loadGltfMesh(const std::string& path, const MeshLoadOptions& options) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) fail(path, "no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open for reading");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const fs::path folder = fs::path(path).parent_path();
    return parseGltfMesh(bytes, path, folder.empty() ? std::string(".") : folder.string(), options);
}

}  // namespace knit
