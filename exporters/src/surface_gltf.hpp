// surface_gltf.hpp (internal) — the surface level in a glTF model: the base-mesh triangles with
// the baked knit material (knit/surface_export.hpp says what is written). Used by exportSurface
// (a GLB of its own) and by the curve / tube glTF writer (a view's surface level beside its
// plies, in one file).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/surface_export.hpp"

namespace tinygltf {
class Model;
}

namespace knit::impl {

// Throws knit::Error starting with `where` for a mesh without UV triangles, indices out of range,
// images that do not match their size, or bad material options.
void validateSurfaceData(const BaseMesh& mesh, const SurfaceImages& images, const SurfaceExportOptions& options,
                         const std::string& where);

// One glTF vertex per distinct (position, uv) pair of the face corners, float32 relative to the
// mesh's bounding-box centre, and the two textures encoded as PNG.
struct SurfaceData {
    std::vector<float> positions, normals, tangents, texcoords;  // xyz, xyz, xyzw, st
    std::vector<uint32_t> indices;
    glm::dvec3 origin{0.0};
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    std::vector<unsigned char> colourPng, normalPng;
    SurfaceExportOptions material;
    size_t vertexCount() const { return positions.size() / 3; }
    // Buffer bytes of addSurface (views 4-byte aligned).
    uint64_t bytes() const;
};
SurfaceData prepareSurface(const BaseMesh& mesh, const SurfaceImages& images, const SurfaceExportOptions& options);

// Appends `bytes` of data to the model's buffer (4-byte aligned) as a new bufferView with that
// target (0: none) and returns its index.
using AddView = std::function<int(const void* data, size_t bytes, int target)>;

// Adds the surface to `model`: its sampler (REPEAT, mipmaps), two textures, the material "knit
// surface", a mesh with one TRIANGLES primitive and a node at the data's origin. Returns the
// node's index; the caller puts it into a scene or under a parent node.
int addSurface(tinygltf::Model& model, const AddView& addView, const SurfaceData& data);

}  // namespace knit::impl
