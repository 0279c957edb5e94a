// polygon_triangulation.cpp — a mesh file's polygon face split into triangles inside it (see
// polygon_triangulation.hpp). Compiled with the exact-predicate code (knit_exact), since it uses
// CGAL's predicates and its constrained Delaunay triangulation.
#include "polygon_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <deque>

namespace knit::impl {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, CGAL::Triangulation_face_base_with_info_2<bool, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Newell's normal (twice the vector area) of the polygon, about its first corner for precision.
glm::dvec3 newellNormal(const std::vector<glm::dvec3>& p) {
    glm::dvec3 n(0.0);
    for (size_t i = 0; i < p.size(); ++i) n += glm::cross(p[i] - p[0], p[(i + 1) % p.size()] - p[0]);
    return n;
}

// The corners in the plane through the first corner perpendicular to `normal`, seen from its
// tip: a polygon wound counter-clockwise about the normal stays counter-clockwise.
std::vector<Point> projected(const std::vector<glm::dvec3>& p, const glm::dvec3& normal) {
    const glm::dvec3 n = glm::normalize(normal);
    const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(a, n)), v = glm::cross(n, u);  // u x v = n
    std::vector<Point> q;
    q.reserve(p.size());
    for (const glm::dvec3& x : p) q.emplace_back(glm::dot(x - p[0], u), glm::dot(x - p[0], v));
    return q;
}

// Whether some corner turns right (strict: a reflex corner) / every corner turns left.
bool someCornerTurns(const std::vector<Point>& q, CGAL::Orientation turn) {
    const size_t n = q.size();
    for (size_t i = 0; i < n; ++i)
        if (CGAL::orientation(q[(i + n - 1) % n], q[i], q[(i + 1) % n]) == turn) return true;
    return false;
}
bool hasReflexCorner(const std::vector<Point>& q) { return someCornerTurns(q, CGAL::RIGHT_TURN); }
bool allCornersTurnLeft(const std::vector<Point>& q) {
    return !someCornerTurns(q, CGAL::RIGHT_TURN) && !someCornerTurns(q, CGAL::COLLINEAR);
}

// Marks the faces inside the polygon: those reached from the infinite face only across polygon
// edges (the constraints). Exact for a simple polygon, whatever the triangles' shapes.
void markInside(Cdt& cdt) {
    for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = true;
    std::deque<Cdt::Face_handle> queue{cdt.infinite_face()};
    cdt.infinite_face()->info() = false;
    while (!queue.empty()) {
        const Cdt::Face_handle f = queue.front();
        queue.pop_front();
        for (int e = 0; e < 3; ++e) {
            const Cdt::Face_handle g = f->neighbor(e);
            if (g->info() && !cdt.is_constrained(Cdt::Edge(f, e))) {
                g->info() = false;
                queue.push_back(g);
            }
        }
    }
}

// The constrained Delaunay triangles of a simple counter-clockwise polygon that lie inside it.
std::vector<std::array<uint32_t, 3>> insideTriangles(const std::vector<Point>& q) {
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> corner(q.size());
    for (size_t i = 0; i < q.size(); ++i) {
        corner[i] = cdt.insert(q[i]);
        corner[i]->info() = uint32_t(i);
    }
    for (size_t i = 0; i < q.size(); ++i) cdt.insert_constraint(corner[i], corner[(i + 1) % q.size()]);
    markInside(cdt);
    std::vector<std::array<uint32_t, 3>> out;
    for (Cdt::Face_handle f : cdt.finite_face_handles())
        if (f->info()) out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    return out;
}

}  // namespace

PolygonTriangles triangulatePolygon(const std::vector<glm::dvec3>& corners) {
    PolygonTriangles out;
    const size_t n = corners.size();
    if (n == 3) {
        out.triangles.push_back({0, 1, 2});
        return out;
    }
    // Step 1: the best-fit plane; a polygon without area has none.
    const glm::dvec3 normal = newellNormal(corners);
    double perimeter = 0;
    for (size_t i = 0; i < n; ++i) perimeter += glm::length(corners[(i + 1) % n] - corners[i]);
    if (!(glm::length(normal) > 1e-12 * perimeter * perimeter)) {
        out.problem = "has no area (its corners are collinear, or it crosses itself so that its parts cancel)";
        return out;
    }
    // Step 2: project; refuse polygons that cross or touch themselves. (A quad turning strictly
    // left at every corner winds once, so it is convex and simple: the common case skips the sweep.)
    const std::vector<Point> q = projected(corners, normal);
    const bool convexQuad = n == 4 && allCornersTurnLeft(q);
    if (!convexQuad && !CGAL::Polygon_2<K>(q.begin(), q.end()).is_simple()) {
        out.problem = "crosses or touches itself (seen along its normal)";
        return out;
    }
    // Step 3: a convex polygon keeps the fan; a concave one is triangulated inside its outline.
    if (convexQuad || !hasReflexCorner(q)) {
        for (uint32_t k = 1; k + 1 < n; ++k) out.triangles.push_back({0, k, k + 1});
        return out;
    }
    out.triangles = insideTriangles(q);
    if (out.triangles.size() != n - 2) {
        out.triangles.clear();
        out.problem = "could not be split into triangles inside it";
    }
    return out;
}

}  // namespace knit::impl
