// sceneStats: the counts, vertices per level, segment lengths and stage times of a built scene.
#include "knit/scene.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace knit {
namespace {

SegmentStats segmentStats(const Polylines& curves) {
    std::vector<double> lengths;
    lengths.reserve(curves.pointCount());
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t b = curves.begin(c), n = curves.size(c);
        for (uint32_t s = 0; s < curves.segmentCount(c); ++s)
            lengths.push_back(glm::distance(curves.points[b + s], curves.points[b + (s + 1) % n]));
    }
    SegmentStats st;
    st.segments = lengths.size();
    if (lengths.empty()) return st;
    const auto mid = lengths.begin() + lengths.size() / 2;
    std::nth_element(lengths.begin(), mid, lengths.end());
    st.medianLength = *mid;
    st.longestLength = *std::max_element(lengths.begin(), lengths.end());
    return st;
}

// The tiles the yarns come from: the island tilings when UV islands overlap, else the one tiling.
size_t tileCount(const SceneStages& stages) {
    if (stages.islandTilings.empty()) return stages.tiling.tiles.size();
    size_t count = 0;
    for (const Tiling& t : stages.islandTilings) count += t.tiles.size();
    return count;
}

constexpr size_t kCurvePointBytes = 16;  // float32 xyz + radius
constexpr size_t kTriangleBytes = 12, kSurfaceVertexBytes = 32;

}  // namespace

// The levels of a scene: with a view, from its cell levels and pieces; else every cell is at the
// ply level with all yarns and plies.
LevelStats levelStats(const Scene& s) {
    LevelStats st;
    const size_t plyVertices = s.plies().curves.pointCount();
    if (!s.detail()) {
        st.plies = {s.grid().cells.size(), s.yarns().curves.pointCount(), plyVertices, plyVertices * kCurvePointBytes};
        return st;
    }
    const SceneDetail& d = *s.detail();
    for (DetailLevel l : d.levels.level) {
        if (l == DetailLevel::Plies) ++st.plies.cells;
        if (l == DetailLevel::Yarns) ++st.yarns.cells;
        if (l == DetailLevel::Surface) ++st.surface.cells;
        if (l == DetailLevel::Culled) ++st.culledCells;
    }
    st.plies.yarnVertices = d.pieces.plies.curves.pointCount();
    st.plies.plyVertices = plyVertices;
    st.plies.bytes = plyVertices * kCurvePointBytes;
    st.yarns.yarnVertices = d.pieces.yarns.curves.pointCount();
    st.yarns.bytes = st.yarns.yarnVertices * kCurvePointBytes;
    std::vector<uint32_t> used;
    for (uint32_t f : d.pieces.surfaceFaces)
        for (int c = 0; c < 3; ++c) used.push_back(s.mesh().faces[f][c]);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    st.surface.bytes = d.pieces.surfaceFaces.size() * kTriangleBytes + used.size() * kSurfaceVertexBytes;
    return st;
}

SceneStats sceneStats(const Scene& s) {
    SceneStats st;
    // Step 1: counts of each stage's results.
    st.cells = s.grid().cells.size();
    st.tiles = tileCount(s.stages());
    st.yarns = s.yarns().curves.curveCount();
    st.tiledYarns = s.stages().uvYarns.yarnCount();
    st.bind = s.bindStats();
    // Step 2: vertices per level (UV yarns, mapped yarns, plies).
    st.tiledVertices = s.stages().uvYarns.vertexCount();
    st.yarnVertices = s.yarns().curves.pointCount();
    st.plyVertices = s.plies().curves.pointCount();
    // Step 3: segment lengths of the yarns, and of the plies when there are any.
    st.yarnSegments = segmentStats(s.yarns().curves);
    if (s.plies().curves.curveCount() > 0) st.plySegments = segmentStats(s.plies().curves);
    // Step 4: cells, vertices and bytes per level of detail.
    st.levels = levelStats(s);
    // Step 5: wall time per stage and in all.
    st.stageTimes = s.timings();
    for (const StageTime& t : s.timings()) st.totalSeconds += t.seconds;
    return st;
}

}  // namespace knit
