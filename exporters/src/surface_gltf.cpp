// surface_gltf.cpp — the surface level's mesh, material and textures in a glTF model.
#include "surface_gltf.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <stb/stb_image_write.h>
#include <tiny_gltf.h>

#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit::impl {
namespace {

// TANGENT: xyz along increasing u (the normal map's +x), w the sign that makes
// w cross(NORMAL, TANGENT) point along increasing v (the map's +y, the image's up: glTF's t
// decreases there), from the triangles' UV gradients accumulated per vertex.
void addTangents(const BaseMesh& mesh, SurfaceData& v) {
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

void addVertices(const BaseMesh& mesh, glm::dvec2 repeats, SurfaceData& v) {
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

uint64_t padded(uint64_t bytes) { return (bytes + 3) / 4 * 4; }

int addAccessor(tinygltf::Model& model, const AddView& addView, const void* data, size_t bytes, int componentType,
                int type, size_t count, int target) {
    tinygltf::Accessor a;
    a.bufferView = addView(data, bytes, target);
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

// A PNG image in the buffer and a texture on sampler `sampler`.
int addTexture(tinygltf::Model& model, const AddView& addView, const std::vector<unsigned char>& png, const char* name,
               int sampler) {
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = addView(png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.source = int(model.images.size()) - 1;
    texture.sampler = sampler;
    model.textures.push_back(texture);
    return int(model.textures.size()) - 1;
}

int addMaterial(tinygltf::Model& model, const AddView& addView, const SurfaceData& d) {
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
    model.samplers.push_back(sampler);
    const int s = int(model.samplers.size()) - 1;
    const SurfaceExportOptions& o = d.material;
    tinygltf::Material mat;
    mat.name = "knit surface";
    mat.pbrMetallicRoughness.baseColorTexture.index =
        addTexture(model, addView, d.colourPng, "knit albedo and coverage", s);
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = o.roughness;
    mat.normalTexture.index = addTexture(model, addView, d.normalPng, "knit normal", s);
    mat.normalTexture.scale = o.normalScale;
    mat.alphaMode = o.alphaMode == SurfaceAlpha::Mask ? "MASK" : "BLEND";
    mat.alphaCutoff = o.alphaCutoff;
    mat.doubleSided = true;
    model.materials.push_back(mat);
    return int(model.materials.size()) - 1;
}

}  // namespace

void validateSurfaceData(const BaseMesh& mesh, const SurfaceImages& im, const SurfaceExportOptions& o,
                         const std::string& where) {
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

uint64_t SurfaceData::bytes() const {
    const size_t n = vertexCount();
    const uint64_t index = n <= 65535 ? 2 : 4;
    return padded(positions.size() * 4) + padded(normals.size() * 4) + padded(tangents.size() * 4) +
           padded(texcoords.size() * 4) + padded(indices.size() * index) + padded(colourPng.size()) +
           padded(normalPng.size());
}

SurfaceData prepareSurface(const BaseMesh& mesh, const SurfaceImages& images, const SurfaceExportOptions& options) {
    SurfaceData d;
    addVertices(mesh, options.repeats, d);
    d.colourPng = encodePng(images.baseColorRgba, images.width, images.height, 4);
    d.normalPng = encodePng(images.normalRgb, images.width, images.height, 3);
    d.material = options;
    return d;
}

int addSurface(tinygltf::Model& model, const AddView& addView, const SurfaceData& v) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = addMaterial(model, addView, v);
    const size_t n = v.vertexCount();
    const int f = TINYGLTF_COMPONENT_TYPE_FLOAT, array = TINYGLTF_TARGET_ARRAY_BUFFER;
    prim.attributes["POSITION"] =
        addAccessor(model, addView, v.positions.data(), v.positions.size() * 4, f, TINYGLTF_TYPE_VEC3, n, array);
    model.accessors.back().minValues = {v.lo[0], v.lo[1], v.lo[2]};
    model.accessors.back().maxValues = {v.hi[0], v.hi[1], v.hi[2]};
    prim.attributes["NORMAL"] =
        addAccessor(model, addView, v.normals.data(), v.normals.size() * 4, f, TINYGLTF_TYPE_VEC3, n, array);
    prim.attributes["TANGENT"] =
        addAccessor(model, addView, v.tangents.data(), v.tangents.size() * 4, f, TINYGLTF_TYPE_VEC4, n, array);
    prim.attributes["TEXCOORD_0"] =
        addAccessor(model, addView, v.texcoords.data(), v.texcoords.size() * 4, f, TINYGLTF_TYPE_VEC2, n, array);
    if (n <= 65535) {
        const std::vector<uint16_t> shorts(v.indices.begin(), v.indices.end());
        prim.indices =
            addAccessor(model, addView, shorts.data(), shorts.size() * 2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                        TINYGLTF_TYPE_SCALAR, shorts.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    } else {
        prim.indices =
            addAccessor(model, addView, v.indices.data(), v.indices.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                        TINYGLTF_TYPE_SCALAR, v.indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    tinygltf::Mesh mesh;
    mesh.name = "knit surface";
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = "knit surface";
    node.mesh = int(model.meshes.size()) - 1;
    node.translation = {v.origin.x, v.origin.y, v.origin.z};
    model.nodes.push_back(node);
    return int(model.nodes.size()) - 1;
}

}  // namespace knit::impl
