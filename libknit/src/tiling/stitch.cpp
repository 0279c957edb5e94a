// Stitch: walk the tiled pattern graph (degree <= 2) into maximal yarns, keeping closed loops.
#include "knit/stitch.hpp"

#include "knit/error.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace knit {
namespace {

struct Walker {
    const Pattern& pattern;
    const PatternAdjacency& adj;
    const Tiling& tiling;
    uint32_t n;  // pattern vertices per tile

    // Neighbour of tiled vertex (tile slot k, local v) through adjacency slot s, or -1.
    int64_t neighbor(uint32_t k, uint32_t v, int s) const {
        const PatternNeighbor& nb = adj.slots[v][s];
        if (nb.v < 0) return -1;
        const int32_t k2 = tiling.slotOf(tiling.tiles[k] + glm::ivec2(nb.dx, nb.dy));
        return k2 < 0 ? -1 : int64_t(k2) * n + nb.v;
    }
    // The neighbour through slot s when its tile is missing from the tiling.
    std::optional<std::pair<glm::ivec2, uint32_t>> missing(uint32_t k, uint32_t v, int s) const {
        if (s < 0) return std::nullopt;
        const PatternNeighbor& nb = adj.slots[v][s];
        if (nb.v < 0) return std::nullopt;
        const glm::ivec2 t = tiling.tiles[k] + glm::ivec2(nb.dx, nb.dy);
        if (tiling.slotOf(t) >= 0) return std::nullopt;
        return std::make_pair(t, uint32_t(nb.v));
    }
    // The slot of w that leads back along the edge we arrived by (from v via slot s).
    int backSlot(uint32_t v, int s, uint32_t w) const {
        const PatternNeighbor& e = adj.slots[v][s];
        for (int t = 0; t < 2; ++t) {
            const PatternNeighbor& b = adj.slots[w][t];
            if (b.v == int32_t(v) && b.dx == -e.dx && b.dy == -e.dy) return t;
        }
        assert(false && "adjacency is symmetric");
        return 0;
    }
};

// Step 3 of stitchYarns: drops the walked yarns (ids, offsets, closed flags, ghosts) with no
// vertex in a tile marked in `keepTile`, in place, keeping the others in order.
void keepFiltered(UvYarns& out, const std::vector<uint8_t>& keepTile, uint32_t n) {
    size_t kept = 0, at = 0;
    for (size_t y = 0; y < out.yarnCount(); ++y) {
        const uint32_t b = out.offsets[y], e = out.offsets[y + 1];
        const bool keep = std::any_of(out.source.begin() + b, out.source.begin() + e,
                                      [&](uint32_t id) { return keepTile[id / n] != 0; });
        if (!keep) continue;
        if (at != b) std::copy(out.source.begin() + b, out.source.begin() + e, out.source.begin() + long(at));
        at += e - b;
        out.closed[kept] = out.closed[y];
        out.ghosts[kept] = out.ghosts[y];
        out.offsets[++kept] = uint32_t(at);
    }
    out.source.resize(at);
    out.source.shrink_to_fit();
    out.offsets.resize(kept + 1);
    out.closed.resize(kept);
    out.ghosts.resize(kept);
}

}  // namespace

UvYarns stitchYarns(const Pattern& pattern, const PatternAdjacency& adj, const Tiling& tiling,
                    const PatternPlacement& placement, const StitchFilter* filter) {
    UvYarns out;
    if (filter != nullptr && filter->keepTile.size() != tiling.tiles.size())
        throw Error("cannot stitch the pattern tiles: the filter has " + std::to_string(filter->keepTile.size()) +
                    " tile marks for " + std::to_string(tiling.tiles.size()) + " tiles");
    const uint32_t n = uint32_t(pattern.points.size());
    const uint64_t total = uint64_t(tiling.tiles.size()) * n;
    if (total == 0) return out;
    const Walker walker{pattern, adj, tiling, n};
    const glm::dvec2 toUv(1.0 / (placement.repeats.x * pattern.px), 1.0 / (placement.repeats.y * pattern.py));

    // The walk (serial) records only the order of the tiled vertex ids (`source`); their uv,
    // height and twist are filled in afterwards, in parallel.
    out.source.reserve(total);
    std::vector<uint8_t> visited(total, 0);

    auto uvOf = [&](glm::ivec2 tile, uint32_t v) {
        const glm::dvec3& q = pattern.points[v];
        return glm::dvec2((q.x + tile.x * pattern.px) * toUv.x, (q.y + tile.y * pattern.py) * toUv.y);
    };
    auto ghostOf = [&](uint64_t id, int slot) {
        GhostVertex g;
        if (const auto m = walker.missing(uint32_t(id / n), uint32_t(id % n), slot)) {
            g.present = true;
            g.uv = uvOf(m->first, m->second);
            g.height = pattern.points[m->second].z * placement.scale;
            g.twist = pattern.twist[m->second];
        }
        return g;
    };
    auto emit = [&](uint64_t id) {
        out.source.push_back(uint32_t(id));
        visited[id] = 1;
    };

    // Walks from `start`, leaving through adjacency slot `out` (-1: none); true for a loop.
    GhostVertex endGhost;
    auto walk = [&](uint64_t start, int out) {
        uint64_t cur = start;
        endGhost = GhostVertex{};
        for (;;) {
            emit(cur);
            if (out < 0) return false;
            const uint32_t v = uint32_t(cur % n);
            const int64_t next = walker.neighbor(uint32_t(cur / n), v, out);
            if (next < 0) {
                endGhost = ghostOf(cur, out);
                return false;
            }
            if (visited[next]) return uint64_t(next) == start;
            // Leave the next vertex through the slot we did not arrive by.
            out = 1 - walker.backSlot(v, out, uint32_t(next % n));
            cur = uint64_t(next);
        }
    };

    auto finishYarn = [&](bool closed, GhostVertex startGhost) {
        out.offsets.push_back(uint32_t(out.source.size()));
        out.closed.push_back(closed ? 1 : 0);
        out.ghosts.push_back({closed ? GhostVertex{} : startGhost, closed ? GhostVertex{} : endGhost});
    };

    // 1. Open yarns start at vertices with fewer than two present neighbours.
    for (uint64_t id = 0; id < total; ++id) {
        if (visited[id]) continue;
        const uint32_t k = uint32_t(id / n), v = uint32_t(id % n);
        const bool has0 = walker.neighbor(k, v, 0) >= 0, has1 = walker.neighbor(k, v, 1) >= 0;
        if (has0 && has1) continue;
        // The start's other slot may lead into a tile that was not generated.
        const int outSlot = has0 ? 0 : (has1 ? 1 : -1);
        const GhostVertex startGhost = ghostOf(id, outSlot == 0 ? 1 : 0);
        walk(id, outSlot);
        finishYarn(false, startGhost);
    }
    // 2. What remains lies on closed loops.
    for (uint64_t id = 0; id < total; ++id) {
        if (visited[id]) continue;
        const bool closed = walk(id, 0);
        finishYarn(closed, GhostVertex{});
    }
    std::vector<uint8_t>().swap(visited);
    // 3. With a filter: only the yarns with a vertex in a kept tile (their order kept).
    if (filter != nullptr) keepFiltered(out, filter->keepTile, n);
    if (filter != nullptr && filter->beforeAllocate) filter->beforeAllocate(out.source.size());
    // 4. Per-vertex data of every kept id, in parallel.
    const size_t count = out.source.size();
    const bool coloured = !pattern.colour.empty();
    tbb::parallel_invoke([&] { out.uv.resize(count); }, [&] { out.height.resize(count); },
                         [&] { out.twist.resize(count); }, [&] { out.colour.resize(coloured ? count : 0); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const uint32_t id = out.source[i], k = id / n, v = id % n;
            out.uv[i] = uvOf(tiling.tiles[k], v);
            out.height[i] = pattern.points[v].z * placement.scale;
            out.twist[i] = pattern.twist[v];
            if (coloured) out.colour[i] = pattern.colour[v];
        }
    });
    return out;
}

void appendIslandYarns(UvYarns& yarns, const UvYarns& more, uint32_t island) {
    const size_t base = yarns.vertexCount();
    if (base + more.vertexCount() > UINT32_MAX)
        throw Error("more than 2^32-1 pattern vertices tiled over all UV islands; lower the repeats");
    yarns.island.resize(yarns.yarnCount(), UINT32_MAX);  // earlier yarns without an island: any
    yarns.ghosts.resize(yarns.yarnCount());
    yarns.uv.insert(yarns.uv.end(), more.uv.begin(), more.uv.end());
    yarns.height.insert(yarns.height.end(), more.height.begin(), more.height.end());
    yarns.twist.insert(yarns.twist.end(), more.twist.begin(), more.twist.end());
    yarns.colour.insert(yarns.colour.end(), more.colour.begin(), more.colour.end());
    yarns.source.insert(yarns.source.end(), more.source.begin(), more.source.end());
    for (size_t y = 0; y < more.yarnCount(); ++y) {
        yarns.offsets.push_back(uint32_t(base + more.offsets[y + 1]));
        yarns.closed.push_back(more.closed[y]);
        yarns.ghosts.push_back(y < more.ghosts.size() ? more.ghosts[y] : std::array<GhostVertex, 2>{});
        yarns.island.push_back(island);
    }
}

}  // namespace knit
