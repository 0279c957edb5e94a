// Sparse UV grid (cell -> triangles, cell -> UV boundary edges) and robust point location.
#include "knit/uv_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"
#include "uv_folds.hpp"
#include "util/csr.hpp"

namespace knit {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;

[[gnu::noinline]] int orientationSign(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return int(CGAL::orientation(Point2(a.x, a.y), Point2(b.x, b.y), Point2(c.x, c.y)));
}

// Orientation of (a, b, c): the double determinant when its sign is certain (Shewchuk's
// error bound for orient2d), otherwise CGAL's exact predicate. Same result as the exact
// predicate, without its call overhead in the common case.
inline int filteredOrientation(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    const double left = (a.x - c.x) * (b.y - c.y), right = (a.y - c.y) * (b.x - c.x);
    const double det = left - right;
    const double bound = 3.3306690738754716e-16 * (std::abs(left) + std::abs(right));
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return orientationSign(a, b, c);
}

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

// Separating-axis test of a triangle against an axis-aligned box (closed sets), in double.
// Callers pass a slightly grown box so rounding can only add cells (conservative).
bool triangleTouchesBox(const glm::dvec2 t[3], glm::dvec2 lo, glm::dvec2 hi) {
    const glm::dvec2 tmin = glm::min(t[0], glm::min(t[1], t[2])), tmax = glm::max(t[0], glm::max(t[1], t[2]));
    if (tmax.x < lo.x || tmin.x > hi.x || tmax.y < lo.y || tmin.y > hi.y) return false;
    const glm::dvec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    for (int e = 0; e < 3; ++e) {
        const glm::dvec2 a = t[e], b = t[(e + 1) % 3], c = t[(e + 2) % 3];
        const glm::dvec2 axis(-(b - a).y, (b - a).x);
        const double side = glm::dot(axis, c - a);
        double bmin = INFINITY, bmax = -INFINITY;
        for (const glm::dvec2& q : corners) {
            const double d = glm::dot(axis, q - a);
            bmin = std::min(bmin, d);
            bmax = std::max(bmax, d);
        }
        // Triangle projects onto [min(0, side), max(0, side)].
        if (bmax < std::min(0.0, side) || bmin > std::max(0.0, side)) return false;
    }
    return true;
}

struct UnionFind {
    std::vector<uint32_t> parent;
    explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

// Whether the interiors of two non-degenerate UV triangles overlap, exactly: they do not iff some
// edge line of one has the other triangle entirely on its far side (closed: touching along an
// edge or at a vertex is not an overlap). For two triangles the edge lines are the only
// separating lines that need testing.
bool interiorsOverlap(const glm::dvec2 s[3], int so, const glm::dvec2 t[3], int to) {
    auto separates = [](const glm::dvec2 a[3], int o, const glm::dvec2 b[3]) {
        for (int e = 0; e < 3; ++e) {
            const glm::dvec2 p = a[e], q = a[(e + 1) % 3];
            if (filteredOrientation(p, q, b[0]) * o <= 0 && filteredOrientation(p, q, b[1]) * o <= 0 &&
                filteredOrientation(p, q, b[2]) * o <= 0)
                return true;
        }
        return false;
    };
    return !separates(s, so, t) && !separates(t, to, s);
}

// Pairs (a < b) of UV islands whose triangles overlap in UV, sorted. Tested only where two islands
// share a grid cell; a pair is tested only while one of its islands is not yet known to overlap
// anything, so every overlapping island appears in some pair, there are at most islandCount pairs,
// and a cell crowded with tiny overlapping islands costs a flag lookup per pair once they are known.
std::vector<glm::uvec2> overlappingChartPairs(const BaseMesh& mesh, const UvGrid& grid) {
    std::vector<glm::uvec2> pairs;
    if (grid.islandCount < 2) return pairs;
    std::vector<char> overlaps(grid.islandCount, 0);
    struct Tri {
        glm::dvec2 v[3];
        glm::dvec2 lo, hi;
    };
    std::vector<Tri> tris;
    for (size_t c = 0; c < grid.cells.size(); ++c) {
        const uint32_t b = grid.triOffsets[c], e = grid.triOffsets[c + 1];
        bool mixed = false;
        for (uint32_t i = b + 1; i < e && !mixed; ++i)
            mixed = grid.islandOfFace[grid.triangles[i]] != grid.islandOfFace[grid.triangles[b]];
        if (!mixed) continue;
        // The cell's UV triangles with their bounding boxes (a cheap, exact pre-test).
        tris.resize(e - b);
        for (uint32_t i = b; i < e; ++i) {
            const glm::uvec3 t = mesh.faceUvs[grid.triangles[i]];
            Tri& r = tris[i - b];
            r.v[0] = mesh.uvs[t.x];
            r.v[1] = mesh.uvs[t.y];
            r.v[2] = mesh.uvs[t.z];
            r.lo = glm::min(r.v[0], glm::min(r.v[1], r.v[2]));
            r.hi = glm::max(r.v[0], glm::max(r.v[1], r.v[2]));
        }
        for (uint32_t i = b; i < e; ++i)
            for (uint32_t j = i + 1; j < e; ++j) {
                const uint32_t f = grid.triangles[i], g = grid.triangles[j];
                const uint32_t cf = grid.islandOfFace[f], cg = grid.islandOfFace[g];
                if (cf == cg || (overlaps[cf] && overlaps[cg]) || grid.faceOrientation[f] == 0 ||
                    grid.faceOrientation[g] == 0)
                    continue;
                const Tri &s = tris[i - b], &t = tris[j - b];
                if (s.hi.x <= t.lo.x || t.hi.x <= s.lo.x || s.hi.y <= t.lo.y || t.hi.y <= s.lo.y)
                    continue;  // no interior overlap
                if (interiorsOverlap(s.v, grid.faceOrientation[f], t.v, grid.faceOrientation[g])) {
                    pairs.emplace_back(std::min(cf, cg), std::max(cf, cg));
                    overlaps[cf] = overlaps[cg] = 1;
                }
            }
    }
    std::sort(pairs.begin(), pairs.end(),
              [](glm::uvec2 x, glm::uvec2 y) { return x.x != y.x ? x.x < y.x : x.y < y.y; });
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}

// Two faces sharing the UV edge of half-edges he and hg: folded when their third corners lie on
// the same side of the edge (exact), whatever the faces' winding.
impl::UvEdgeLink edgeLink(const BaseMesh& mesh, uint32_t he, uint32_t hg) {
    auto corner = [&](uint32_t h, uint32_t step) { return mesh.uvs[mesh.faceUvs[h / 3][(h % 3 + step) % 3]]; };
    const glm::dvec2 a = corner(he, 0), b = corner(he, 1);
    const int se = filteredOrientation(a, b, corner(he, 2)), sg = filteredOrientation(a, b, corner(hg, 2));
    return {he / 3, hg / 3, se != 0 && se == sg};
}

}  // namespace

glm::ivec2 UvGrid::cellOf(glm::dvec2 uv) const {
    auto axis = [](double x, double size) {
        const double f = std::floor(x / size);
        if (!(f > -1e9)) return int32_t(-1000000000);  // also NaN
        if (f > 1e9) return int32_t(1000000000);
        return int32_t(f);
    };
    return {axis(uv.x, cellSize.x), axis(uv.y, cellSize.y)};
}

int32_t UvGrid::slotOf(glm::ivec2 cell) const {
    const glm::ivec2 r = cell - minCell;
    if (r.x < 0 || r.y < 0 || r.x >= dims.x || r.y >= dims.y) return -1;
    return cellSlot[size_t(r.y) * size_t(dims.x) + size_t(r.x)];
}

uint64_t uvGridEntryBound(const BaseMesh& mesh, glm::dvec2 cellSize) {
    UvGrid cells;
    cells.cellSize = cellSize;
    uint64_t total = 0;
    for (const glm::uvec3& t : mesh.faceUvs) {
        const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
        if (orientationSign(a, b, c) == 0) continue;  // never listed
        const glm::ivec2 c0 = cells.cellOf(glm::min(a, glm::min(b, c)));
        const glm::ivec2 c1 = cells.cellOf(glm::max(a, glm::max(b, c)));
        const uint64_t n = uint64_t(int64_t(c1.x) - c0.x + 1) * uint64_t(int64_t(c1.y) - c0.y + 1);
        total = n > std::numeric_limits<uint64_t>::max() - total ? std::numeric_limits<uint64_t>::max() : total + n;
    }
    return total;
}

UvGrid buildUvGrid(const BaseMesh& mesh, const UvGridOptions& options) {
    if (!util::positiveFinite(options.cellSize))
        throw Error(
            "UV grid: the pattern period in UV, from the repeats or the physical size, must be positive and finite");
    UvGrid grid;
    grid.cellSize = options.cellSize;
    const size_t nf = mesh.faces.size();
    if (nf == 0) return grid;
    const glm::dvec2 eps = 1e-9 * options.cellSize;

    // 1. Per-face UV orientation (exact) and the bounding box of touched cells.
    grid.faceOrientation.resize(nf);
    glm::ivec2 lo(INT32_MAX), hi(INT32_MIN);
    for (size_t f = 0; f < nf; ++f) {
        const glm::uvec3 t = mesh.faceUvs[f];
        grid.faceOrientation[f] = int8_t(orientationSign(mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]));
        if (grid.faceOrientation[f] == 0) {
            ++grid.degenerateUvFaces;
            continue;
        }
        const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
        lo = glm::min(lo, grid.cellOf(glm::min(a, glm::min(b, c))));
        hi = glm::max(hi, grid.cellOf(glm::max(a, glm::max(b, c))));
    }
    if (grid.degenerateUvFaces == nf) throw Error(mesh.name + ": every triangle has zero UV area");
    const uint64_t cellCount = uint64_t(hi.x - lo.x + 1) * uint64_t(hi.y - lo.y + 1);
    if (cellCount > options.maxCells) {
        std::ostringstream msg;
        msg << mesh.name << ": the UV grid would span " << cellCount << " pattern cells (limit " << options.maxCells
            << "); the repeats are too large for this mesh's UV range";
        throw Error(msg.str());
    }
    grid.minCell = lo;
    grid.dims = hi - lo + 1;
    const uint64_t entryBound = uvGridEntryBound(mesh, options.cellSize);
    if (entryBound > options.maxEntries) {
        std::ostringstream msg;
        msg << mesh.name << ": its UV triangles would be listed in up to " << entryBound
            << " pattern cells in total (limit " << options.maxEntries
            << "): triangles far larger than a pattern cell, or stacked on each other; use fewer repeats or a finer "
               "mesh";
        throw Error(msg.str());
    }

    // 2. Conservative triangle-cell overlap: candidate cells from the UV box (cellOf is monotone,
    //    so every point of the triangle maps into this range), then a separating-axis test
    //    against the cell box grown by eps, so rounding can only add cells, never drop one.
    std::vector<std::pair<uint64_t, uint32_t>> cellFace;  // (linear cell, face)
    cellFace.reserve(entryBound);
    for (size_t f = 0; f < nf; ++f) {
        if (grid.faceOrientation[f] == 0) continue;
        const glm::uvec3 t = mesh.faceUvs[f];
        const glm::dvec2 tri[3] = {mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]};
        const glm::ivec2 c0 = grid.cellOf(glm::min(tri[0], glm::min(tri[1], tri[2])));
        const glm::ivec2 c1 = grid.cellOf(glm::max(tri[0], glm::max(tri[1], tri[2])));
        for (int32_t y = c0.y; y <= c1.y; ++y)
            for (int32_t x = c0.x; x <= c1.x; ++x) {
                const glm::dvec2 boxLo = glm::dvec2(x, y) * options.cellSize - eps;
                const glm::dvec2 boxHi = glm::dvec2(x + 1, y + 1) * options.cellSize + eps;
                if (c0 == c1 || triangleTouchesBox(tri, boxLo, boxHi))
                    cellFace.emplace_back(uint64_t(y - lo.y) * uint64_t(grid.dims.x) + uint64_t(x - lo.x), uint32_t(f));
            }
    }
    std::sort(cellFace.begin(), cellFace.end());
    grid.cellSlot.assign(cellCount, -1);
    for (size_t i = 0; i < cellFace.size(); ++i) {
        if (i == 0 || cellFace[i].first != cellFace[i - 1].first) {
            if (i > 0) grid.triOffsets.push_back(uint32_t(grid.triangles.size()));
            grid.cellSlot[cellFace[i].first] = int32_t(grid.cells.size());
            const uint64_t lin = cellFace[i].first;
            grid.cells.push_back(
                lo + glm::ivec2(int32_t(lin % uint64_t(grid.dims.x)), int32_t(lin / uint64_t(grid.dims.x))));
        }
        grid.triangles.push_back(cellFace[i].second);
    }
    grid.triOffsets.push_back(uint32_t(grid.triangles.size()));

    // 3. UV edges shared by two non-degenerate faces are interior; the rest are boundary.
    //    Faces sharing a UV edge belong to the same island.
    std::vector<std::pair<uint64_t, uint32_t>> edges;  // (undirected uv edge key, half-edge)
    edges.reserve(3 * nf);
    for (size_t f = 0; f < nf; ++f) {
        if (grid.faceOrientation[f] == 0) continue;
        const glm::uvec3 t = mesh.faceUvs[f];
        const uint32_t v[3] = {t.x, t.y, t.z};
        for (int k = 0; k < 3; ++k) {
            const uint64_t a = v[k], b = v[(k + 1) % 3];
            edges.emplace_back((std::min(a, b) << 32) | std::max(a, b), uint32_t(3 * f + k));
        }
    }
    std::sort(edges.begin(), edges.end());
    UnionFind islands(nf);
    std::vector<std::pair<uint64_t, uint32_t>> cellEdge;  // (linear cell, boundary half-edge)
    std::vector<impl::UvEdgeLink> links;                  // manifold UV edges, for fold detection
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j].first == edges[i].first) ++j;
        for (size_t k = i + 1; k < j; ++k) islands.unite(edges[i].second / 3, edges[k].second / 3);
        if (j - i == 2) links.push_back(edgeLink(mesh, edges[i].second, edges[i + 1].second));
        if (j - i == 1) {
            const uint32_t he = edges[i].second, f = he / 3, k = he % 3;
            const glm::uvec3 t = mesh.faceUvs[f];
            const uint32_t v[3] = {t.x, t.y, t.z};
            const glm::dvec2 a = mesh.uvs[v[k]], b = mesh.uvs[v[(k + 1) % 3]];
            const glm::ivec2 c0 = grid.cellOf(glm::min(a, b) - eps), c1 = grid.cellOf(glm::max(a, b) + eps);
            for (int32_t y = c0.y; y <= c1.y; ++y)
                for (int32_t x = c0.x; x <= c1.x; ++x)
                    if (grid.slotOf({x, y}) >= 0) cellEdge.emplace_back(uint64_t(grid.slotOf({x, y})), he);
        }
        i = j;
    }
    std::sort(cellEdge.begin(), cellEdge.end());
    grid.edgeOffsets.assign(grid.cells.size() + 1, 0);
    for (const auto& ce : cellEdge) ++grid.edgeOffsets[ce.first + 1];
    util::countsToOffsets(grid.edgeOffsets);
    grid.boundaryEdges.reserve(cellEdge.size());
    for (const auto& ce : cellEdge) grid.boundaryEdges.push_back(ce.second);

    // Islands numbered 0, 1, ... in the order of their lowest face.
    grid.islandOfFace.resize(nf);
    std::vector<uint32_t> islandOfRoot(nf, UINT32_MAX);
    for (size_t f = 0; f < nf; ++f) {
        uint32_t& id = islandOfRoot[islands.find(uint32_t(f))];
        if (id == UINT32_MAX) id = grid.islandCount++;
        grid.islandOfFace[f] = id;
    }
    grid.overlappingIslands = overlappingChartPairs(mesh, grid);

    // 4. Islands that fold over themselves (reported, see UvGrid::foldedUvFaces).
    const impl::UvFolds folds =
        impl::findUvFolds(mesh, grid.islandOfFace, grid.islandCount, grid.faceOrientation, links);
    grid.foldedUvFaces = folds.faces;
    grid.foldedUvFaceExample = folds.example;
    return grid;
}

namespace {

// Barycentrics of p in triangle (a, b, c), clamped to the closed triangle.
inline glm::dvec3 clampedBarycentrics(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 p) {
    const double den = cross2(b - a, c - a);
    double l1 = cross2(p - a, c - a) / den, l2 = cross2(b - a, p - a) / den;
    double l0 = 1.0 - l1 - l2;
    l0 = std::max(l0, 0.0);
    l1 = std::max(l1, 0.0);
    l2 = std::max(l2, 0.0);
    const double s = l0 + l1 + l2;
    return glm::dvec3(l0, l1, l2) / s;
}

// Closest point of segment [a, b] to p: parameter in [0, 1].
double closestOnSegment(glm::dvec2 a, glm::dvec2 b, glm::dvec2 p) {
    const glm::dvec2 d = b - a;
    const double len2 = glm::dot(d, d);
    return len2 > 0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
}

}  // namespace

LocateResult locatePoint(const BaseMesh& mesh, const UvGrid& grid, glm::dvec2 uv, double tolerance, uint32_t hint,
                         uint32_t island) {
    LocateResult result;
    if (!util::finite(uv) || grid.cells.empty()) return result;
    const bool anyIsland = island == kAnyIsland;
    auto skip = [&](uint32_t f) { return !anyIsland && grid.islandOfFace[f] != island; };

    // 0. Strictly inside the hint triangle: no other non-overlapping triangle contains it.
    if (hint < grid.faceOrientation.size() && grid.faceOrientation[hint] != 0 && !skip(hint)) {
        const glm::uvec3 t = mesh.faceUvs[hint];
        const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
        const int o = grid.faceOrientation[hint];
        if (filteredOrientation(a, b, uv) == o && filteredOrientation(b, c, uv) == o &&
            filteredOrientation(c, a, uv) == o) {
            result.status = LocateStatus::Inside;
            result.point = {hint, clampedBarycentrics(a, b, c, uv)};
            return result;
        }
    }

    // 1. Exact containment in the closed triangle; the lowest triangle id wins (lists ascend).
    if (const int32_t slot = grid.slotOf(grid.cellOf(uv)); slot >= 0) {
        for (uint32_t i = grid.triOffsets[slot]; i < grid.triOffsets[slot + 1]; ++i) {
            const uint32_t f = grid.triangles[i];
            if (skip(f)) continue;
            const glm::uvec3 t = mesh.faceUvs[f];
            const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
            const int o = grid.faceOrientation[f];
            if (filteredOrientation(a, b, uv) == -o) continue;
            if (filteredOrientation(b, c, uv) == -o) continue;
            if (filteredOrientation(c, a, uv) == -o) continue;
            result.status = LocateStatus::Inside;
            result.point = {f, clampedBarycentrics(a, b, c, uv)};
            return result;
        }
    }
    if (!(tolerance > 0)) return result;

    // 2. Closest triangle within the tolerance (ties: lowest id), with clamped barycentrics.
    //    The search window is bounded by the grid's cells: nothing lies beyond them.
    const glm::ivec2 c0 = glm::max(grid.cellOf(uv - tolerance), grid.minCell);
    const glm::ivec2 c1 = glm::min(grid.cellOf(uv + tolerance), grid.minCell + grid.dims - 1);
    double best = tolerance;
    bool found = false;
    for (int32_t y = c0.y; y <= c1.y; ++y)
        for (int32_t x = c0.x; x <= c1.x; ++x) {
            const int32_t slot = grid.slotOf({x, y});
            if (slot < 0) continue;
            for (uint32_t i = grid.triOffsets[slot]; i < grid.triOffsets[slot + 1]; ++i) {
                const uint32_t f = grid.triangles[i];
                if (skip(f)) continue;
                const glm::uvec3 t = mesh.faceUvs[f];
                const glm::dvec2 v[3] = {mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]};
                for (int e = 0; e < 3; ++e) {
                    const double s = closestOnSegment(v[e], v[(e + 1) % 3], uv);
                    const double d = glm::distance(uv, v[e] + s * (v[(e + 1) % 3] - v[e]));
                    if (d < best || (d == best && found && f < result.point.face)) {
                        best = d;
                        found = true;
                        glm::dvec3 bary(0.0);
                        bary[e] = 1.0 - s;
                        bary[(e + 1) % 3] = s;
                        result.point = {f, bary};
                    }
                }
            }
        }
    if (found) {
        result.status = LocateStatus::Clamped;
        result.distance = best;
    }
    return result;
}

}  // namespace knit
