// binding_boundary.cpp — UV segments against the boundary edges of a UV island (see
// binding_boundary.hpp).
#include "binding_boundary.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace knit::impl {
namespace {

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

// Calls visit(halfEdge, t, s) for every boundary edge of `island` that the UV segment p -> q
// crosses or touches (t along p -> q, s along the edge; both within [-slack, 1 + slack]),
// looking only at the cells in [c0, c1]. Parallel edges are skipped: running along the
// boundary stays in the island.
template <class Visit>
void forEachBoundaryCrossing(const BaseMesh& mesh, const UvGrid& grid, uint32_t island, glm::dvec2 p, glm::dvec2 q,
                             glm::ivec2 c0, glm::ivec2 c1, double slack, Visit visit) {
    const glm::dvec2 d = q - p;
    for (int32_t y = c0.y; y <= c1.y; ++y)
        for (int32_t x = c0.x; x <= c1.x; ++x) {
            const int32_t slot = grid.slotOf({x, y});
            if (slot < 0) continue;
            for (uint32_t i = grid.edgeOffsets[slot]; i < grid.edgeOffsets[slot + 1]; ++i) {
                const uint32_t he = grid.boundaryEdges[i], f = he / 3, k = he % 3;
                if (grid.islandOfFace[f] != island) continue;
                const glm::uvec3 t = mesh.faceUvs[f];
                const uint32_t corner[3] = {t.x, t.y, t.z};
                const glm::dvec2 a = mesh.uvs[corner[k]], e = mesh.uvs[corner[(k + 1) % 3]] - a;
                const double den = cross2(d, e);
                if (den == 0) continue;
                const double tt = cross2(a - p, e) / den, s = cross2(a - p, d) / den;
                if (tt < -slack || tt > 1 + slack || s < -slack || s > 1 + slack) continue;
                visit(he, tt, s);
            }
        }
}

// True when p lies in a (closed) UV triangle of `island` listed in p's cell (double precision
// with a relative tolerance: it decides only the middle of a segment piece, see leavesIsland).
bool insideIsland(const BaseMesh& mesh, const UvGrid& grid, uint32_t island, glm::dvec2 p) {
    const int32_t slot = grid.slotOf(grid.cellOf(p));
    if (slot < 0) return false;
    for (uint32_t i = grid.triOffsets[slot]; i < grid.triOffsets[slot + 1]; ++i) {
        const uint32_t f = grid.triangles[i];
        if (grid.islandOfFace[f] != island) continue;
        const glm::uvec3 t = mesh.faceUvs[f];
        const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
        const double den = cross2(b - a, c - a);
        const double l1 = cross2(p - a, c - a) / den, l2 = cross2(b - a, p - a) / den, l0 = 1.0 - l1 - l2;
        const double eps = -1e-12;
        if (l0 >= eps && l1 >= eps && l2 >= eps) return true;
    }
    return false;
}

}  // namespace

std::optional<BoundVertex> boundaryCrossing(const BaseMesh& mesh, const UvGrid& grid, uint32_t island,
                                            const UvStep& step) {
    const glm::dvec2 p = step.p, q = step.q;
    // The closest crossing along p -> q (the lowest half-edge on ties).
    double bestT = INFINITY;
    uint32_t bestEdge = UINT32_MAX;
    double bestS = 0;
    forEachBoundaryCrossing(mesh, grid, island, p, q, grid.cellOf(glm::min(p, q)), grid.cellOf(glm::max(p, q)), 1e-12,
                            [&](uint32_t he, double tt, double s) {
                                if (tt < bestT || (tt == bestT && he < bestEdge)) {
                                    bestT = std::clamp(tt, 0.0, 1.0);
                                    bestEdge = he;
                                    bestS = std::clamp(s, 0.0, 1.0);
                                }
                            });
    if (bestEdge == UINT32_MAX || bestT < 1e-9) return std::nullopt;
    // The vertex on that edge: barycentrics of its two corners, height and twist along the step.
    BoundVertex b;
    b.face = bestEdge / 3;
    b.bary = glm::dvec3(0.0);
    b.bary[bestEdge % 3] = 1.0 - bestS;
    b.bary[(bestEdge % 3 + 1) % 3] = bestS;
    b.height = step.hp + bestT * (step.hq - step.hp);
    b.twist = step.tp + bestT * (step.tq - step.tp);
    b.origin = 0;  // set by the caller, which knows the yarn vertex
    return b;
}

bool leavesIsland(const BaseMesh& mesh, const UvGrid& grid, uint32_t island, glm::dvec2 p, glm::dvec2 q, glm::ivec2 cp,
                  glm::ivec2 cq, double tol, std::vector<double>& ts) {
    const glm::ivec2 c0 = glm::min(cp, cq), c1 = glm::max(cp, cq);  // cellOf is monotone
    if (c0 == c1) {  // fast path: a step inside one cell without boundary edges
        const int32_t slot = grid.slotOf(c0);
        if (slot < 0 || grid.edgeOffsets[slot] == grid.edgeOffsets[slot + 1]) return false;
    }
    // The boundary crossings strictly inside the step, in order, then the step's end.
    const glm::dvec2 d = q - p;
    ts.clear();
    forEachBoundaryCrossing(mesh, grid, island, p, q, c0, c1, 0.0, [&](uint32_t, double tt, double) {
        if (tt > 0 && tt < 1) ts.push_back(tt);
    });
    if (ts.empty()) return false;
    std::sort(ts.begin(), ts.end());
    ts.push_back(1.0);
    // The middle of each piece between crossings, away from the ends, must lie in the island.
    const double len = glm::length(d);
    double prev = 0.0;
    for (const double t : ts) {
        const double mid = 0.5 * (prev + t);
        const bool nearEnd = mid * len <= tol || (1.0 - mid) * len <= tol;
        if (t > prev && !nearEnd && !insideIsland(mesh, grid, island, p + mid * d)) return true;
        prev = t;
    }
    return false;
}

}  // namespace knit::impl
