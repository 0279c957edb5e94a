// Pattern placement in UV space and the set of tiles a mesh needs.
#include "knit/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"

namespace knit {

PatternPlacement placePattern(const Pattern& pattern, const BaseMesh& mesh, const PlacementOptions& options) {
    const glm::dvec2 r = options.repeats;
    const bool physical = r.x == 0.0 && r.y == 0.0;
    if (!physical && !util::positiveFinite(r)) {
        std::ostringstream msg;
        msg << "repeats (" << r.x << ", " << r.y << ") must both be positive (or both 0 for the pattern's physical size)";
        throw Error(msg.str());
    }
    const glm::dvec2 metresPerUv = uvToMetreScale(mesh);
    if (!(metresPerUv.x > 0 && metresPerUv.y > 0))
        throw Error(mesh.name + ": cannot place the pattern: the mesh has no triangle with non-degenerate UVs and 3D area");
    PatternPlacement placement;
    placement.repeats = physical ? metresPerUv / glm::dvec2(pattern.px, pattern.py) : r;
    if (placement.repeats.x > 1e7 || placement.repeats.y > 1e7) {
        std::ostringstream msg;
        msg << "repeats (" << placement.repeats.x << ", " << placement.repeats.y << ") exceed 1e7 periods per UV unit";
        throw Error(msg.str());
    }
    // Physical size of one period on the mesh relative to the pattern's own period.
    const double sx = metresPerUv.x / (placement.repeats.x * pattern.px);
    const double sy = metresPerUv.y / (placement.repeats.y * pattern.py);
    placement.scale = std::sqrt(sx * sy);
    return placement;
}

namespace {

Tiling tilingFromMarks(glm::ivec2 minTile, glm::ivec2 dims, std::vector<int32_t> marks) {
    Tiling t;
    t.minTile = minTile;
    t.dims = dims;
    t.tileSlot = std::move(marks);
    for (int32_t y = 0; y < dims.y; ++y)
        for (int32_t x = 0; x < dims.x; ++x) {
            int32_t& slot = t.tileSlot[size_t(y) * size_t(dims.x) + size_t(x)];
            if (slot < 0) continue;
            slot = int32_t(t.tiles.size());
            t.tiles.push_back(minTile + glm::ivec2(x, y));
        }
    return t;
}

}  // namespace

TileReach tileReach(const Pattern& pattern, glm::dvec2 margin) {
    if (!(margin.x >= 0 && margin.x <= pattern.px)) margin.x = margin.x > pattern.px ? pattern.px : 0.0;
    if (!(margin.y >= 0 && margin.y <= pattern.py)) margin.y = margin.y > pattern.py ? pattern.py : 0.0;
    glm::ivec2 lo(INT32_MAX), hi(INT32_MIN);
    for (const glm::dvec3& q : pattern.points) {
        const glm::ivec2 c0(int32_t(std::floor((q.x - margin.x) / pattern.px)), int32_t(std::floor((q.y - margin.y) / pattern.py)));
        const glm::ivec2 c1(int32_t(std::floor((q.x + margin.x) / pattern.px)), int32_t(std::floor((q.y + margin.y) / pattern.py)));
        lo = glm::min(lo, c0);
        hi = glm::max(hi, c1);
    }
    return {lo, hi};
}

Tiling tilesForCells(const Pattern& pattern, const std::vector<glm::ivec2>& cells, glm::dvec2 margin) {
    if (cells.empty()) return {};
    // Range of cells (relative to its own tile) that the pattern's vertices, grown by the
    // margin, fall into.
    const TileReach reach = tileReach(pattern, margin);
    const glm::ivec2 lo = reach.lo, hi = reach.hi;
    // Tile t reaches cells t + [lo, hi]; so cell c needs tiles c - hi .. c - lo.
    glm::ivec2 cmin = cells[0], cmax = cells[0];
    for (const glm::ivec2& c : cells) {
        cmin = glm::min(cmin, c);
        cmax = glm::max(cmax, c);
    }
    const glm::ivec2 minTile = cmin - hi, dims = (cmax - lo) - minTile + 1;
    std::vector<int32_t> marks(size_t(dims.x) * size_t(dims.y), -1);
    for (const glm::ivec2& c : cells)
        for (int32_t y = c.y - hi.y; y <= c.y - lo.y; ++y)
            for (int32_t x = c.x - hi.x; x <= c.x - lo.x; ++x)
                marks[size_t(y - minTile.y) * size_t(dims.x) + size_t(x - minTile.x)] = 0;
    return tilingFromMarks(minTile, dims, std::move(marks));
}

Tiling tilesForRegion(glm::ivec2 first, glm::ivec2 last, bool periodic) {
    if (last.x < first.x || last.y < first.y) return {};
    const glm::ivec2 dims = last - first + 1;
    Tiling t = tilingFromMarks(first, dims, std::vector<int32_t>(size_t(dims.x) * size_t(dims.y), 0));
    t.periodic = periodic;
    return t;
}

}  // namespace knit
