// buildScene's stages (names, order, progress) and Scene::fromParts.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "common/fixtures.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

std::vector<std::string> stageNames(const Scene& s) {
    std::vector<std::string> names;
    for (const StageTime& t : s.timings()) names.push_back(t.stage);
    return names;
}

TEST(Scene, stagesRunInPipelineOrderAndReportProgress) {
    SceneOptions o;
    o.mesh = "plane";
    o.placement.repeats = {3, 3};
    std::vector<std::pair<std::string, int>> calls;
    int total = 0;
    o.progress = [&](const std::string& stage, int index, int n) {
        calls.emplace_back(stage, index);
        total = n;
    };
    const Scene s = buildScene(o);
    const std::vector<std::string> all = {"load_pattern", "load_mesh", "normals",  "uv_grid", "tiling",
                                          "stitch",       "binding",   "evaluate", "plies"};
    EXPECT_EQ(stageNames(s), all);
    ASSERT_EQ(calls.size(), all.size());
    for (size_t k = 0; k < calls.size(); ++k) {
        EXPECT_EQ(calls[k].first, all[k]);
        EXPECT_EQ(calls[k].second, int(k));
    }
    EXPECT_EQ(total, 9);
}

TEST(Scene, inMemoryInputsWithoutPliesSkipTheLoadAndPlyStages) {
    SceneOptions o;
    o.placement.repeats = {3, 3};
    o.buildPlies = false;
    int total = 0;
    o.progress = [&](const std::string&, int, int n) { total = n; };
    const Scene s = buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, 4), o);
    EXPECT_EQ(stageNames(s),
              (std::vector<std::string>{"normals", "uv_grid", "tiling", "stitch", "binding", "evaluate"}));
    EXPECT_EQ(total, 6);
    EXPECT_EQ(s.plies().curves.curveCount(), 0u);
    // The ply settings carry the scene's yarn radius, unresolved (their consumer resolves them).
    EXPECT_EQ(s.plyOptions().yarnRadius, s.yarnRadius());
    EXPECT_EQ(s.plyOptions().pitch, 0.0);
    EXPECT_GT(s.yarns().curves.curveCount(), 0u);
    EXPECT_EQ(s.binding().vertexCount(), s.yarns().curves.pointCount());
    EXPECT_GT(s.stages().uvYarns.vertexCount(), 0u);
    EXPECT_TRUE(s.stages().islandTilings.empty());  // one island
}

TEST(Scene, fromPartsKeepsThePartsAndLeavesThePipelineResultsEmpty) {
    SceneParts p;
    p.mesh = test::planeMesh(test::Triangulation::Regular, 2);
    p.normals.assign(p.mesh.positions.size(), glm::dvec3(0, 0, 1));
    p.yarnRadius = 0.002;
    p.grid.cellSize = glm::dvec2(0.25);
    const glm::dvec3 line[2] = {{0, 0.05, 0}, {0.1, 0.05, 0}};
    p.yarns.curves.addCurve(line, 2, false);
    p.binding.face = {0, 1};
    const Scene s = Scene::fromParts(std::move(p));
    EXPECT_EQ(s.mesh().faceCount(), 8u);
    EXPECT_EQ(s.normals().size(), 9u);
    EXPECT_EQ(s.yarnRadius(), 0.002);
    EXPECT_EQ(s.grid().cellSize, glm::dvec2(0.25));
    EXPECT_EQ(s.yarns().curves.pointCount(), 2u);
    EXPECT_EQ(s.binding().face, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(s.plyOptions().yarnRadius, 0.002);
    EXPECT_TRUE(s.pattern().points.empty());
    EXPECT_TRUE(s.timings().empty());
    EXPECT_EQ(s.stages().uvYarns.vertexCount(), 0u);
    EXPECT_EQ(s.bindStats().closedLoops, 0u);
}

}  // namespace
}  // namespace knit
