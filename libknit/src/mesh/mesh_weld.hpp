// mesh_weld.hpp (internal) — polygons with per-corner UVs to a welded, triangulated BaseMesh;
// shared by the OBJ/PLY/OFF readers (mesh_reader.hpp) and glTF (mesh_gltf.cpp).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"

namespace knit::impl {

// Polygon k has the corners [faceStart[k], faceStart[k + 1]) of `faceVerts` (indices into
// `points`); corner c's texture coordinate is uvOfCorner(c). The caller has validated the input:
// indices in range, >= 3 distinct vertices per polygon, finite positions and UVs.
// Positions that are exactly equal (-0 == +0) are welded when options.weldEqualPositions is set;
// unreferenced positions are dropped; a UV vertex is one distinct (position, uv) pair, numbered in
// first-use order; polygons are triangulated inside their outline (triangulatePolygon: convex
// ones as the fan (v0, vi, vi+1)). A polygon that cannot be (no area, crossing itself) is
// refused as `name: faceName(k) <problem>` (faceName defaults to "face k").
BaseMesh weldPolygons(const std::string& name, const std::vector<glm::dvec3>& points,
                      const std::vector<uint32_t>& faceStart, const std::vector<int>& faceVerts,
                      const std::function<glm::dvec2(uint32_t corner)>& uvOfCorner, const MeshLoadOptions& options,
                      const std::function<std::string(size_t face)>& faceName = nullptr);

}  // namespace knit::impl
