// exportSurface: the base mesh with the baked knit textures as a glTF PBR material, one GLB.
#include "knit/surface_export.hpp"

#include <cmath>
#include <cstring>
#include <sstream>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <stb/stb_image_write.h>
#include <tiny_gltf.h>

#include "atomic_file.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

void validateSurface(const BaseMesh& mesh, const SurfaceImages& im, const SurfaceExportOptions& o) {
    const std::string where = "cannot export '" + o.path + "': ";
    checkSurfaceOutput(o.path);
    if (mesh.faces.empty() || mesh.faceUvs.size() != mesh.faces.size() || mesh.uvs.empty())
        throw Error(where + "base mesh '" + mesh.name + "' has no triangles with UVs");
    for (size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (mesh.faces[f][k] >= mesh.positions.size() || mesh.faceUvs[f][k] >= mesh.uvs.size())
                throw Error(where + "base mesh '" + mesh.name + "' triangle " + std::to_string(f) +
                            " refers to a vertex or UV that does not exist");
    const size_t pixels = size_t(std::max(im.width, 0)) * size_t(std::max(im.height, 0));
    if (pixels == 0 || im.baseColorRgba.size() != 4 * pixels || im.normalRgb.size() != 3 * pixels)
        throw Error(where + "the baked images are empty or do not match their size " + std::to_string(im.width) +
                    " x " + std::to_string(im.height));
    if (!util::positiveFinite(o.repeats)) throw Error(where + "texture repeats must be positive and finite");
    if (!(o.alphaCutoff >= 0 && o.alphaCutoff <= 1)) throw Error(where + "alpha cutoff must be in [0, 1]");
    if (!(o.roughness >= 0 && o.roughness <= 1)) throw Error(where + "roughness must be in [0, 1]");
    if (!util::finite(o.normalScale)) throw Error(where + "normal scale must be finite");
}

// One glTF vertex per distinct (position, uv) pair of the face corners.
struct SurfaceVertices {
    std::vector<float> positions, normals, tangents, texcoords;  // xyz, xyz, xyzw, st
    std::vector<uint32_t> indices;
    glm::dvec3 origin{0.0};
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

// TANGENT: xyz along increasing u (the normal map's +x), w the sign that makes
// w cross(NORMAL, TANGENT) point along increasing v (the map's +y, the image's up: glTF's t
// decreases there), from the triangles' UV gradients accumulated per vertex.
void addTangents(const BaseMesh& mesh, SurfaceVertices& v) {
    const size_t n = v.positions.size() / 3;
    std::vector<glm::dvec3> du(n, glm::dvec3(0.0)), dv(n, glm::dvec3(0.0));
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
        const glm::uvec3 p = mesh.faces[f], t = mesh.faceUvs[f];
        const glm::dvec3 e1 = mesh.positions[p.y] - mesh.positions[p.x], e2 = mesh.positions[p.z] - mesh.positions[p.x];
        const glm::dvec2 w1 = mesh.uvs[t.y] - mesh.uvs[t.x], w2 = mesh.uvs[t.z] - mesh.uvs[t.x];
        const double det = w1.x * w2.y - w2.x * w1.y;
        if (det == 0 || !std::isfinite(det)) continue;
        const glm::dvec3 gu = (e1 * w2.y - e2 * w1.y) / det, gv = (e2 * w1.x - e1 * w2.x) / det;
        for (int k = 0; k < 3; ++k) du[v.indices[3 * f + k]] += gu, dv[v.indices[3 * f + k]] += gv;
    }
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 normal(v.normals[3 * i], v.normals[3 * i + 1], v.normals[3 * i + 2]);
        glm::dvec3 t = du[i] - glm::dot(du[i], normal) * normal;
        t = glm::length(t) > 0 ? glm::normalize(t) : util::anyPerpendicular(normal);
        const double w = glm::dot(glm::cross(normal, t), dv[i]) < 0 ? -1.0 : 1.0;
        v.tangents.insert(v.tangents.end(), {float(t.x), float(t.y), float(t.z), float(w)});
    }
}

SurfaceVertices surfaceVertices(const BaseMesh& mesh, glm::dvec2 repeats) {
    SurfaceVertices v;
    glm::dvec3 lo(mesh.positions.front()), hi(lo);
    for (const glm::dvec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    v.origin = 0.5 * (lo + hi);
    const std::vector<glm::dvec3> normals = vertexNormals(mesh.positions, mesh.faces);
    std::unordered_map<uint64_t, uint32_t> index;
    for (size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t p = mesh.faces[f][k], t = mesh.faceUvs[f][k];
            const auto [it, added] = index.emplace((uint64_t(p) << 32) | t, uint32_t(index.size()));
            v.indices.push_back(it->second);
            if (!added) continue;
            const glm::dvec3 q = mesh.positions[p] - v.origin;
            const glm::dvec3 n = glm::length(normals[p]) > 0 ? glm::normalize(normals[p]) : glm::dvec3(0, 1, 0);
            for (int c = 0; c < 3; ++c) v.positions.push_back(float(q[c])), v.normals.push_back(float(n[c]));
            v.texcoords.push_back(float(mesh.uvs[t].x * repeats.x));
            v.texcoords.push_back(float(1.0 - mesh.uvs[t].y * repeats.y));
        }
    addTangents(mesh, v);
    for (int c = 0; c < 3; ++c) {
        v.lo[c] = v.hi[c] = v.positions[size_t(c)];
        for (size_t i = size_t(c); i < v.positions.size(); i += 3)
            v.lo[c] = std::min(v.lo[c], v.positions[i]), v.hi[c] = std::max(v.hi[c], v.positions[i]);
    }
    return v;
}

std::vector<unsigned char> encodePng(const std::vector<uint8_t>& pixels, int w, int h, int channels) {
    std::vector<unsigned char> out;
    auto append = [](void* context, void* data, int size) {
        auto* o = static_cast<std::vector<unsigned char>*>(context);
        o->insert(o->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &out, w, h, channels, pixels.data(), w * channels))
        throw Error("cannot export the surface: PNG encoding of a " + std::to_string(w) + " x " + std::to_string(h) +
                    " texture failed");
    return out;
}

// The model under construction: one buffer, views appended 4-byte aligned.
class SurfaceModel {
public:
    SurfaceModel() {
        model_.asset.version = "2.0";
        model_.asset.generator = "libknit surface level";
        model_.buffers.emplace_back();
    }

    int addView(const void* data, size_t bytes, int target) {
        std::vector<unsigned char>& b = model_.buffers[0].data;
        while (b.size() % 4) b.push_back(0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = b.size();
        v.byteLength = bytes;
        v.target = target;
        b.insert(b.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + bytes);
        model_.bufferViews.push_back(v);
        return int(model_.bufferViews.size()) - 1;
    }

    int addAccessor(const void* data, size_t bytes, int componentType, int type, size_t count, int target) {
        tinygltf::Accessor a;
        a.bufferView = addView(data, bytes, target);
        a.componentType = componentType;
        a.type = type;
        a.count = count;
        model_.accessors.push_back(a);
        return int(model_.accessors.size()) - 1;
    }

    // A PNG image in the buffer and a texture on the shared REPEAT sampler.
    int addTexture(const std::vector<unsigned char>& png, const char* name) {
        tinygltf::Image image;
        image.name = name;
        image.mimeType = "image/png";
        image.bufferView = addView(png.data(), png.size(), 0);
        model_.images.push_back(image);
        tinygltf::Texture texture;
        texture.source = int(model_.images.size()) - 1;
        texture.sampler = 0;
        model_.textures.push_back(texture);
        return int(model_.textures.size()) - 1;
    }

    tinygltf::Model model_;
};

void addGeometry(SurfaceModel& m, const SurfaceVertices& v) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = 0;
    const size_t n = v.positions.size() / 3;
    prim.attributes["POSITION"] =
        m.addAccessor(v.positions.data(), v.positions.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n,
                      TINYGLTF_TARGET_ARRAY_BUFFER);
    m.model_.accessors.back().minValues = {v.lo[0], v.lo[1], v.lo[2]};
    m.model_.accessors.back().maxValues = {v.hi[0], v.hi[1], v.hi[2]};
    prim.attributes["NORMAL"] = m.addAccessor(v.normals.data(), v.normals.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                              TINYGLTF_TYPE_VEC3, n, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["TANGENT"] = m.addAccessor(v.tangents.data(), v.tangents.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                               TINYGLTF_TYPE_VEC4, n, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["TEXCOORD_0"] =
        m.addAccessor(v.texcoords.data(), v.texcoords.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n,
                      TINYGLTF_TARGET_ARRAY_BUFFER);
    if (n <= 65535) {
        const std::vector<uint16_t> shorts(v.indices.begin(), v.indices.end());
        prim.indices = m.addAccessor(shorts.data(), shorts.size() * 2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                     TINYGLTF_TYPE_SCALAR, shorts.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    } else {
        prim.indices = m.addAccessor(v.indices.data(), v.indices.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                     TINYGLTF_TYPE_SCALAR, v.indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    tinygltf::Mesh mesh;
    mesh.name = "knit surface";
    mesh.primitives.push_back(prim);
    m.model_.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    node.translation = {v.origin.x, v.origin.y, v.origin.z};
    m.model_.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    m.model_.scenes.push_back(scene);
    m.model_.defaultScene = 0;
}

size_t addMaterial(SurfaceModel& m, const SurfaceImages& im, const SurfaceExportOptions& o) {
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
    m.model_.samplers.push_back(sampler);
    const std::vector<unsigned char> colour = encodePng(im.baseColorRgba, im.width, im.height, 4);
    const std::vector<unsigned char> normal = encodePng(im.normalRgb, im.width, im.height, 3);
    tinygltf::Material mat;
    mat.name = "knit surface";
    mat.pbrMetallicRoughness.baseColorTexture.index = m.addTexture(colour, "knit albedo and coverage");
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = o.roughness;
    mat.normalTexture.index = m.addTexture(normal, "knit normal");
    mat.normalTexture.scale = o.normalScale;
    mat.alphaMode = o.alphaMode == SurfaceAlpha::Mask ? "MASK" : "BLEND";
    mat.alphaCutoff = o.alphaCutoff;
    mat.doubleSided = true;
    m.model_.materials.push_back(mat);
    return colour.size() + normal.size();
}

}  // namespace

void checkSurfaceOutput(const std::string& path) {
    if (util::lowerExtension(path) != "glb")
        throw Error("cannot export '" + path +
                    "': the surface level (--surface-only) is written as GLB only (use a .glb name)");
    detail::checkOutputFolder(path);
}

SurfaceExportStats exportSurface(const BaseMesh& mesh, const SurfaceImages& images, const SurfaceExportOptions& o) {
    // Step 1: validate everything before any file exists.
    validateSurface(mesh, images, o);
    // Step 2: vertices, the material with its PNG textures, one buffer.
    const SurfaceVertices v = surfaceVertices(mesh, o.repeats);
    SurfaceModel m;
    addGeometry(m, v);
    SurfaceExportStats stats;
    stats.imageBytes = addMaterial(m, images, o);
    stats.vertices = v.positions.size() / 3;
    stats.triangles = v.indices.size() / 3;
    // Step 3: GLB through a temporary file, renamed when complete.
    detail::AtomicFile file(o.path, true);
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&m.model_, file.stream(), false, true))
        throw Error("cannot export '" + o.path + "': tinygltf failed to write the GLB");
    file.commit();
    stats.bytes = size_t(file.bytesWritten());
    return stats;
}

}  // namespace knit
