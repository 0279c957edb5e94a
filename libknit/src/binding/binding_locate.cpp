// binding_locate.cpp — binding phase 1: point location of the yarn vertices and the steps that
// leave their island (see binding_locate.hpp).
#include "binding_locate.hpp"

#include <algorithm>
#include <new>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binding_boundary.hpp"

namespace knit::impl {
namespace {

static_assert(std::is_trivially_destructible_v<LocateResult>, "loc is freed without destructors");

// Constructs loc[b, e): each vertex located with the previous one's triangle as the hint.
void locateYarn(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, size_t y, double tolUv,
                LocateResult* loc) {
    const size_t b = yarns.offsets[y], e = yarns.offsets[y + 1];
    const uint32_t only = yarns.island.empty() ? kAnyIsland : yarns.island[y];
    uint32_t hint = UINT32_MAX;
    for (size_t i = b; i < e; ++i) {
        LocateResult r = locatePoint(mesh, grid, yarns.uv[i], tolUv, hint, only);
        // A yarn tiled for one island is not clamped onto it from inside another island:
        // that point belongs to the other island's own yarns.
        if (r.status == LocateStatus::Clamped && only != kAnyIsland) {
            const LocateResult any = locatePoint(mesh, grid, yarns.uv[i], 0.0);
            if (any.status == LocateStatus::Inside && grid.islandOfFace[any.point.face] != only) r = LocateResult{};
        }
        new (loc + i) LocateResult(r);
        hint = loc[i].status == LocateStatus::Inside ? loc[i].point.face : UINT32_MAX;
    }
}

// Per step i -> i+1 (last -> first on closed yarns) between two vertices of one island: whether
// the step leaves the island. `crossings`: scratch for leavesIsland.
void markStepsLeavingChart(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, size_t y, double tolUv,
                           const LocateResult* loc, std::vector<uint8_t>& leaves, std::vector<double>& crossings) {
    const size_t b = yarns.offsets[y], e = yarns.offsets[y + 1];
    for (size_t i = b; i < e; ++i) {
        const size_t j = i + 1 < e ? i + 1 : b;
        if ((j == b && !yarns.closed[y]) || loc[i].status == LocateStatus::Outside ||
            loc[j].status == LocateStatus::Outside)
            continue;
        // Both inside one (convex) triangle: the step cannot leave it.
        if (loc[i].point.face == loc[j].point.face && loc[i].status == LocateStatus::Inside &&
            loc[j].status == LocateStatus::Inside)
            continue;
        const uint32_t c = grid.islandOfFace[loc[i].point.face];
        if (c == grid.islandOfFace[loc[j].point.face])
            leaves[i] = leavesIsland(mesh, grid, c, yarns.uv[i], yarns.uv[j], grid.cellOf(yarns.uv[i]),
                                     grid.cellOf(yarns.uv[j]), tolUv, crossings);
    }
}

}  // namespace

LocatedYarns locateYarns(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, const LocateOptions& options) {
    const size_t nv = yarns.vertexCount();
    LocatedYarns out;
    out.loc.reset(static_cast<LocateResult*>(std::malloc(std::max<size_t>(nv, 1) * sizeof(LocateResult))));
    if (!out.loc) throw std::bad_alloc();
    out.leaves.assign(nv, 0);
    // Locate, then flag the steps, one yarn at a time (its vertices are still in cache).
    LocateResult* const loc = out.loc.get();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarns.yarnCount(), 1), [&](const tbb::blocked_range<size_t>& r) {
        std::vector<double> crossings;
        for (size_t y = r.begin(); y != r.end(); ++y) {
            locateYarn(mesh, grid, yarns, y, options.toleranceUv, loc);
            markStepsLeavingChart(mesh, grid, yarns, y, options.toleranceUv, loc, out.leaves, crossings);
        }
    });
    // Count the clamped and the cut vertices.
    for (size_t i = 0; i < nv; ++i) {
        if (loc[i].status == LocateStatus::Clamped) ++out.clampedVertices;
        if (!out.located(i)) ++out.outsideVertices;
    }
    return out;
}

}  // namespace knit::impl
