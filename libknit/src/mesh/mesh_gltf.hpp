// mesh_gltf.hpp (internal) — the glTF base-mesh reader (mesh_gltf.cpp) with a hook that poses
// the vertices: glTF animation input (gltf_animation.cpp) gets the same triangles, welding and
// UVs as loadGltfMesh with animated positions.
#pragma once
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "io/gltf_document.hpp"
#include "knit/base_mesh.hpp"

namespace knit::impl {

// The world-space positions of primitive `p` of mesh instance `instance` (one per element of its
// POSITION accessor `position`), replacing world * POSITION.
using GltfPoser = std::function<std::vector<glm::dvec3>(const gltf::MeshInstance& instance, const gltf::Primitive& p,
                                                        const gltf::Accessor& position)>;

// The BaseMesh of the default scene (loadGltfMesh), posed by `poser` when it is not null.
BaseMesh gltfMeshOf(const gltf::Document& doc, const MeshLoadOptions& options, const GltfPoser* poser = nullptr);

}  // namespace knit::impl
