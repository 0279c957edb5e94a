// sceneStats: segment statistics of closed and open curves, the ply section only with plies,
// tiles of overlapping islands, counts and times that agree with the scene.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "common/fixtures.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

// Open curve with segments 1, 2, 3 and a closed square of side 0.5 (4 segments, the closing one
// included).
Polylines openAndClosedCurves() {
    Polylines c;
    const glm::dvec3 open[4] = {{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {6, 0, 0}};
    const glm::dvec3 square[4] = {{0, 0, 1}, {0.5, 0, 1}, {0.5, 0.5, 1}, {0, 0.5, 1}};
    c.addCurve(open, 4, false);
    c.addCurve(square, 4, true);
    return c;
}

TEST(SceneStats, closedCurvesCountTheirClosingSegmentAndTheMedianIsTheUpperOne) {
    SceneParts p;
    p.yarns.curves = openAndClosedCurves();
    const SceneStats st = sceneStats(Scene::fromParts(std::move(p)));
    EXPECT_EQ(st.yarnSegments.segments, 7u);
    EXPECT_EQ(st.yarnSegments.medianLength, 0.5);  // sorted: 0.5 x 4, 1, 2, 3; element 7 / 2
    EXPECT_EQ(st.yarnSegments.longestLength, 3.0);
    EXPECT_EQ(st.yarns, 2u);
    EXPECT_EQ(st.yarnVertices, 8u);
    EXPECT_FALSE(st.plySegments.has_value());  // no plies: no ply section
}

TEST(SceneStats, anEmptySceneHasNoSegmentsAndNoTime) {
    const SceneStats st = sceneStats(Scene());
    EXPECT_EQ(st.yarnSegments.segments, 0u);
    EXPECT_EQ(st.yarnSegments.medianLength, 0.0);
    EXPECT_EQ(st.yarnSegments.longestLength, 0.0);
    EXPECT_FALSE(st.plySegments.has_value());
    EXPECT_TRUE(st.stageTimes.empty());
    EXPECT_EQ(st.totalSeconds, 0.0);
}

TEST(SceneStats, plySegmentsOnlyWhenTheSceneHoldsPlies) {
    SceneParts p;
    const glm::dvec3 single[1] = {{0, 0, 0}};
    p.plies.curves.addCurve(single, 1, false);  // a ply curve without segments still counts
    const SceneStats st = sceneStats(Scene::fromParts(std::move(p)));
    ASSERT_TRUE(st.plySegments.has_value());
    EXPECT_EQ(st.plySegments->segments, 0u);
    EXPECT_EQ(st.plyVertices, 1u);
}

TEST(SceneStats, countsAndTimesAgreeWithTheScene) {
    SceneOptions o;
    o.mesh = "cylinder";
    o.placement.repeats = {9, 5};
    const Scene s = buildScene(o);
    const SceneStats st = sceneStats(s);
    EXPECT_EQ(st.cells, s.grid().cells.size());
    EXPECT_EQ(st.tiles, s.stages().tiling.tiles.size());  // one island: the one tiling
    EXPECT_EQ(st.yarns, s.yarns().curves.curveCount());
    EXPECT_EQ(st.tiledYarns, s.stages().uvYarns.yarnCount());
    EXPECT_EQ(st.tiledVertices, s.stages().uvYarns.vertexCount());
    EXPECT_EQ(st.plyVertices, s.plies().curves.pointCount());
    EXPECT_EQ(st.bind.closedLoops, s.bindStats().closedLoops);
    EXPECT_EQ(st.bind.weldedEnds, s.bindStats().weldedEnds);
    ASSERT_TRUE(st.plySegments.has_value());
    EXPECT_GT(st.plySegments->segments, 0u);
    ASSERT_EQ(st.stageTimes.size(), s.timings().size());
    double total = 0;
    for (size_t k = 0; k < st.stageTimes.size(); ++k) {
        EXPECT_EQ(st.stageTimes[k].stage, s.timings()[k].stage);
        total += s.timings()[k].seconds;
    }
    EXPECT_EQ(st.totalSeconds, total);
}

// Two sheets over the same UV square: the yarns come from one tiling per island, and the tiles
// counted are theirs (twice the shared tiling's), not the shared one's.
TEST(SceneStats, overlappingChartsCountTheTilesOfEveryChart) {
    BaseMesh m = test::planeMesh(test::Triangulation::Regular, 4);
    const BaseMesh upper = m;
    const uint32_t base = uint32_t(m.positions.size());
    for (const glm::dvec3& x : upper.positions) m.positions.push_back(x + glm::dvec3(0, 0, 0.05));
    m.uvs.insert(m.uvs.end(), upper.uvs.begin(), upper.uvs.end());
    for (const glm::uvec3& f : upper.faces) m.faces.push_back(f + base);
    m.faceUvs = m.faces;
    SceneOptions o;
    o.placement.repeats = {5, 5};
    o.buildPlies = false;
    const Scene s = buildScene(generateStockinette(), m, o);
    ASSERT_EQ(s.stages().islandTilings.size(), 2u);
    const SceneStats st = sceneStats(s);
    EXPECT_EQ(st.tiles, s.stages().islandTilings[0].tiles.size() + s.stages().islandTilings[1].tiles.size());
    EXPECT_EQ(st.tiles, 2 * s.stages().tiling.tiles.size());
}

}  // namespace
}  // namespace knit
