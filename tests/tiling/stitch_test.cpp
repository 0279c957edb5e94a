#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>

#include "common/fixtures.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/stitch.hpp"
#include "knit/tiling.hpp"

namespace knit {
namespace {

// Independent loop count of an a x b periodic tiling: every closed component of the pattern on
// the 1x1 torus winds by w = (wx, wy) cells per turn; its lift to the a x b torus closes after
// k turns, k the smallest with k*wx = 0 mod a and k*wy = 0 mod b, giving a*b/k loops.
size_t loopsByWinding(const Pattern& p, int a, int b) {
    std::vector<std::vector<std::pair<size_t, int>>> incident(p.points.size());  // (edge, +1 out / -1 in)
    for (size_t e = 0; e < p.edges.size(); ++e) {
        incident[p.edges[e].v0].push_back({e, +1});
        incident[p.edges[e].v1].push_back({e, -1});
    }
    std::vector<uint8_t> usedEdge(p.edges.size(), 0), seen(p.points.size(), 0);
    size_t loops = 0;
    for (uint32_t start = 0; start < p.points.size(); ++start) {
        if (seen[start] || incident[start].size() != 2) continue;
        int wx = 0, wy = 0;
        uint32_t v = start;
        bool closed = true;
        for (;;) {
            seen[v] = 1;
            auto it =
                std::find_if(incident[v].begin(), incident[v].end(), [&](auto& ie) { return !usedEdge[ie.first]; });
            if (it == incident[v].end()) break;
            const PeriodicEdge& e = p.edges[it->first];
            usedEdge[it->first] = 1;
            wx += it->second * e.dx;
            wy += it->second * e.dy;
            v = it->second > 0 ? e.v1 : e.v0;
            if (incident[v].size() != 2) {
                closed = false;
                break;
            }
        }
        if (!closed) continue;
        int k = 1;
        while (((k * wx) % a + a) % a != 0 || ((k * wy) % b + b) % b != 0) ++k;
        loops += size_t(a * b / k);
    }
    return loops;
}

UvYarns stitchTorus(const Pattern& p, int a, int b) {
    PatternPlacement placement;
    placement.repeats = {double(a), double(b)};
    return stitchYarns(p, buildAdjacency(p), tilesForRegion({0, 0}, {a - 1, b - 1}, true), placement);
}

TEST(Stitch, periodicTilingLoopCountMatchesWindingCount) {
    for (const std::string& file : test::sharedPatternFiles()) {
        const Pattern p = loadPyp(test::sharedPattern(file));
        for (auto [a, b] : {std::pair{1, 1}, {6, 8}, {3, 5}, {4, 4}}) {
            const UvYarns y = stitchTorus(p, a, b);
            const size_t closed = std::accumulate(y.closed.begin(), y.closed.end(), size_t(0));
            EXPECT_EQ(closed, loopsByWinding(p, a, b)) << file << " " << a << "x" << b;
            EXPECT_EQ(closed, y.yarnCount()) << file << ": a torus has no open yarns";
        }
    }
}

TEST(Stitch, stockinetteOnSixByEightTorusHasSixteenLoops) {
    EXPECT_EQ(stitchTorus(loadPyp(test::sharedPattern("stockinette.pyp")), 6, 8).yarnCount(), 16u);
}

TEST(Stitch, everyTiledVertexAppearsExactlyOnce) {
    const Pattern p = loadPyp(test::sharedPattern("slip_stitch_honeycomb.pyp"));
    const Tiling tiling = tilesForCells(p, {{0, 0}, {1, 0}, {2, 0}, {1, 1}, {5, 5}});
    PatternPlacement placement;
    placement.repeats = {8, 8};
    const UvYarns y = stitchYarns(p, buildAdjacency(p), tiling, placement);
    std::vector<int> count(tiling.tiles.size() * p.points.size(), 0);
    for (uint32_t s : y.source) ++count[s];
    for (size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i], 1) << "tiled vertex " << i;
}

TEST(Stitch, noTiledVertexHasDegreeAboveTwo) {
    // Each yarn is a path or cycle: consecutive vertices are pattern neighbours, so in the
    // stitched result every vertex has at most a predecessor and a successor.
    const Pattern p = loadPyp(test::sharedPattern("satin.pyp"));
    const PatternAdjacency adj = buildAdjacency(p);
    const Tiling tiling = tilesForRegion({-1, -2}, {3, 2});
    PatternPlacement placement;
    placement.repeats = {4, 4};
    const UvYarns y = stitchYarns(p, adj, tiling, placement);
    const uint32_t n = uint32_t(p.points.size());
    auto adjacent = [&](uint32_t s, uint32_t t) {
        const glm::ivec2 ts = tiling.tiles[s / n], tt = tiling.tiles[t / n];
        for (const PatternNeighbor& nb : adj.slots[s % n])
            if (nb.v == int32_t(t % n) && ts + glm::ivec2(nb.dx, nb.dy) == tt) return true;
        return false;
    };
    for (size_t yi = 0; yi < y.yarnCount(); ++yi) {
        const uint32_t b = y.offsets[yi], e = y.offsets[yi + 1];
        for (uint32_t i = b; i + 1 < e; ++i) ASSERT_TRUE(adjacent(y.source[i], y.source[i + 1]));
        if (y.closed[yi]) ASSERT_TRUE(adjacent(y.source[e - 1], y.source[b]));
    }
}

TEST(Stitch, openYarnsEndOnlyAtTheTilingBorder) {
    const Pattern p = generateStockinette();
    const Tiling tiling = tilesForRegion({0, 0}, {4, 3});
    PatternPlacement placement;
    placement.repeats = {5, 4};
    const UvYarns y = stitchYarns(p, buildAdjacency(p), tiling, placement);
    // One course per tile row, entering at tile 0 and leaving at tile 4: 4 open yarns.
    EXPECT_EQ(y.yarnCount(), 4u);
    for (size_t yi = 0; yi < y.yarnCount(); ++yi) {
        EXPECT_FALSE(y.closed[yi]);
        EXPECT_EQ(y.offsets[yi + 1] - y.offsets[yi], 5u * p.points.size());
    }
}

TEST(Stitch, alignmentPutsPatternOriginAtUvZero) {
    const Pattern p = generateStockinette();
    PatternPlacement placement;
    placement.repeats = {4, 2};
    placement.scale = 0.5;
    const UvYarns y = stitchYarns(p, buildAdjacency(p), tilesForRegion({2, 1}, {2, 1}), placement);
    ASSERT_EQ(y.vertexCount(), p.points.size());
    for (size_t i = 0; i < y.vertexCount(); ++i) {
        const glm::dvec3 q = p.points[y.source[i] % p.points.size()];
        EXPECT_DOUBLE_EQ(y.uv[i].x, (q.x + 2 * p.px) / (4 * p.px));
        EXPECT_DOUBLE_EQ(y.uv[i].y, (q.y + 1 * p.py) / (2 * p.py));
        EXPECT_DOUBLE_EQ(y.height[i], q.z * 0.5);
    }
}

// A filter keeps exactly the yarns with a vertex in a kept tile, each the unfiltered yarn vertex
// for vertex and in the same order, and tells the kept count before allocating their data.
// Every yarn of `all` with a vertex in a kept tile is in `kept`, in the same order, vertex for
// vertex (ids, uv, ghosts, closed flag), and `kept` has no other yarn. Returns the kept count.
size_t expectKeptYarnsAreTheUnfilteredOnes(const UvYarns& all, const UvYarns& kept,
                                           const std::vector<uint8_t>& keepTile, uint32_t n) {
    size_t k = 0;
    for (size_t y = 0; y < all.yarnCount(); ++y) {
        const auto b = all.source.begin() + all.offsets[y], e = all.source.begin() + all.offsets[y + 1];
        if (!std::any_of(b, e, [&](uint32_t id) { return keepTile[id / n] != 0; })) continue;
        if (k >= kept.yarnCount()) {
            ADD_FAILURE() << "yarn " << y << " through a kept tile is missing";
            return k;
        }
        const auto kb = kept.source.begin() + kept.offsets[k];
        EXPECT_TRUE(std::equal(b, e, kb, kept.source.begin() + kept.offsets[k + 1])) << "yarn " << y;
        EXPECT_TRUE(std::equal(all.uv.begin() + all.offsets[y], all.uv.begin() + all.offsets[y + 1],
                               kept.uv.begin() + kept.offsets[k]));
        EXPECT_EQ(kept.closed[k], all.closed[y]);
        for (int end = 0; end < 2; ++end) {
            EXPECT_EQ(kept.ghosts[k][end].present, all.ghosts[y][end].present) << "yarn " << y;
            EXPECT_EQ(kept.ghosts[k][end].uv, all.ghosts[y][end].uv) << "yarn " << y;
        }
        ++k;
    }
    EXPECT_EQ(k, kept.yarnCount());
    return k;
}

TEST(Stitch, filterKeepsTheYarnsThroughKeptTilesUnchanged) {
    const Pattern p = generateStockinette();
    const Tiling tiling = tilesForRegion({0, 0}, {11, 9});
    PatternPlacement placement;
    placement.repeats = {12, 10};
    const PatternAdjacency adj = buildAdjacency(p);
    const UvYarns all = stitchYarns(p, adj, tiling, placement);
    StitchFilter filter;
    filter.keepTile.assign(tiling.tiles.size(), 0);
    filter.keepTile[size_t(tiling.slotOf({4, 3}))] = 1;
    filter.keepTile[size_t(tiling.slotOf({5, 7}))] = 1;
    uint64_t told = 0;
    filter.beforeAllocate = [&](uint64_t n) { told = n; };
    const UvYarns kept = stitchYarns(p, adj, tiling, placement, &filter);
    const uint32_t n = uint32_t(p.points.size());
    EXPECT_GT(expectKeptYarnsAreTheUnfilteredOnes(all, kept, filter.keepTile, n), 0u);
    EXPECT_LT(kept.vertexCount(), all.vertexCount() / 2);
    EXPECT_EQ(told, kept.vertexCount());
    EXPECT_EQ(kept.uv.size(), kept.vertexCount());
    // A filter for another tiling is refused, in words (no stage name such as "stitching:").
    filter.keepTile.pop_back();
    try {
        stitchYarns(p, adj, tiling, placement, &filter);
        ADD_FAILURE() << "a filter with one tile mark too few was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("cannot stitch the pattern tiles: the filter has ", 0), 0u) << e.what();
    }
}

// The filtered walk follows only the kept yarns, from where the full walk starts them: open yarns
// entered from either end or the middle, and closed loops (a periodic tiling) from any vertex.
TEST(Stitch, filterStartsEachKeptYarnWhereTheFullWalkDoes) {
    const Pattern p = generateStockinette();
    const PatternAdjacency adj = buildAdjacency(p);
    const uint32_t n = uint32_t(p.points.size());
    for (const bool periodic : {false, true}) {
        const Tiling tiling = tilesForRegion({0, 0}, {7, 5}, periodic);
        PatternPlacement placement;
        placement.repeats = {8, 6};
        const UvYarns all = stitchYarns(p, adj, tiling, placement);
        EXPECT_EQ(std::count(all.closed.begin(), all.closed.end(), 1) > 0, periodic);
        // Kept tiles at the border (open ends), inside, and in the last column and row.
        for (const glm::ivec2 tile : {glm::ivec2(0, 0), glm::ivec2(3, 2), glm::ivec2(7, 5), glm::ivec2(6, 1)}) {
            StitchFilter filter;
            filter.keepTile.assign(tiling.tiles.size(), 0);
            filter.keepTile[size_t(tiling.slotOf(tile))] = 1;
            const UvYarns kept = stitchYarns(p, adj, tiling, placement, &filter);
            SCOPED_TRACE(std::string(periodic ? "periodic" : "open") + " tile " + std::to_string(tile.x) + "," +
                         std::to_string(tile.y));
            EXPECT_GT(expectKeptYarnsAreTheUnfilteredOnes(all, kept, filter.keepTile, n), 0u);
            EXPECT_LT(kept.vertexCount(), all.vertexCount());
        }
    }
}

}  // namespace
}  // namespace knit
