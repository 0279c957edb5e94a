// polygon_triangulation.hpp (internal) — one polygon face of a mesh file split into triangles
// that stay inside it (convex or not), or the reason it cannot be.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace knit::impl {

// Triangles of one polygon as corner numbers (0 .. corners-1), wound like the polygon.
struct PolygonTriangles {
    std::vector<std::array<uint32_t, 3>> triangles;
    std::string problem;  // empty when triangulated; else why not ("crosses itself", ...)
};

// Triangles and quads-or-more that are convex (no reflex corner seen along the polygon's
// Newell normal) keep the fan (0, k, k + 1), so meshes of convex faces load as before. A
// concave polygon is projected onto its best-fit plane (Newell normal) and triangulated with
// CGAL's constrained Delaunay triangulation, keeping the triangles inside the polygon. A
// polygon of >= 4 corners with zero area or that crosses or touches itself in that plane
// gets a problem and no triangles.
PolygonTriangles triangulatePolygon(const std::vector<glm::dvec3>& corners);

}  // namespace knit::impl
