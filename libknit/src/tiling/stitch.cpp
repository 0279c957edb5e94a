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

// Where the unfiltered walk of stitchYarns starts a yarn: an open yarn at the lower id of its two
// ends (the first end in id order), a closed loop at its lowest id with slot 0.
struct YarnStart {
    bool closed;
    uint64_t id;
    bool operator<(const YarnStart& o) const { return closed != o.closed ? o.closed : id < o.id; }
};

// Follows the yarn through `id` leaving by `slot`: the end reached (marked in `seen` on the way),
// or nothing when the walk comes back to `id` (a loop; `lowest` is then its lowest id).
std::optional<uint64_t> followYarn(const Walker& w, uint64_t id, int slot, std::vector<uint8_t>& seen,
                                   uint64_t& lowest) {
    uint64_t cur = id;
    lowest = id;
    for (;;) {
        seen[cur] = 1;
        lowest = std::min(lowest, cur);
        const uint32_t v = uint32_t(cur % w.n);
        const int64_t next = w.neighbor(uint32_t(cur / w.n), v, slot);
        if (next < 0) return cur;
        if (uint64_t(next) == id) return std::nullopt;
        slot = 1 - w.backSlot(v, slot, uint32_t(next % w.n));
        cur = uint64_t(next);
    }
}

// The starts of the yarns with a vertex in a kept tile, in the order the unfiltered walk meets
// them (open yarns first). Only those yarns are followed (each twice: here and when walked).
std::vector<YarnStart> yarnStarts(const Walker& w, const std::vector<uint8_t>& keepTile, uint64_t total) {
    std::vector<YarnStart> starts;
    std::vector<uint8_t> seen(total, 0);
    for (uint32_t k = 0; k < keepTile.size(); ++k) {
        if (!keepTile[k]) continue;
        for (uint64_t id = uint64_t(k) * w.n; id < uint64_t(k + 1) * w.n; ++id) {
            if (seen[id]) continue;
            uint64_t lowest = id;
            const std::optional<uint64_t> end0 = followYarn(w, id, 0, seen, lowest);
            if (!end0) {
                starts.push_back({true, lowest});
                continue;
            }
            const std::optional<uint64_t> end1 = followYarn(w, id, 1, seen, lowest);
            starts.push_back({false, std::min(*end0, end1.value_or(*end0))});
        }
    }
    std::sort(starts.begin(), starts.end());
    return starts;
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
    if (filter == nullptr) out.source.reserve(total);
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

    // An open yarn from its end `id` (a vertex with fewer than two present neighbours).
    auto openYarn = [&](uint64_t id) {
        const uint32_t k = uint32_t(id / n), v = uint32_t(id % n);
        const bool has0 = walker.neighbor(k, v, 0) >= 0, has1 = walker.neighbor(k, v, 1) >= 0;
        // The start's other slot may lead into a tile that was not generated.
        const int outSlot = has0 ? 0 : (has1 ? 1 : -1);
        const GhostVertex startGhost = ghostOf(id, outSlot == 0 ? 1 : 0);
        walk(id, outSlot);
        finishYarn(false, startGhost);
    };
    if (filter == nullptr) {
        // 1. Open yarns start at vertices with fewer than two present neighbours.
        for (uint64_t id = 0; id < total; ++id) {
            if (visited[id]) continue;
            const uint32_t k = uint32_t(id / n), v = uint32_t(id % n);
            if (walker.neighbor(k, v, 0) >= 0 && walker.neighbor(k, v, 1) >= 0) continue;
            openYarn(id);
        }
        // 2. What remains lies on closed loops.
        for (uint64_t id = 0; id < total; ++id) {
            if (visited[id]) continue;
            const bool closed = walk(id, 0);
            finishYarn(closed, GhostVertex{});
        }
    } else {
        // 3. With a filter, only the yarns through kept tiles are walked, from the starts the walk
        // above would take, in its order (yarnStarts).
        for (const YarnStart& s : yarnStarts(walker, filter->keepTile, total))
            if (s.closed) {
                finishYarn(walk(s.id, 0), GhostVertex{});
            } else {
                openYarn(s.id);
            }
    }
    std::vector<uint8_t>().swap(visited);
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
