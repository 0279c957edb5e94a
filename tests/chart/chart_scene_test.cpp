// A relaxed chart pattern through the whole pipeline (buildScene), like any other pattern.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "knit/base_mesh.hpp"
#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

TEST(ChartScene, relaxedStockinetteClosesItsCoursesAroundACylinder) {
    const Pattern p = relaxChart(builtinChart("chart:stockinette")).relaxed.pattern;
    SceneOptions o;
    o.placement.repeats = {4, 4};
    o.buildPlies = false;
    const Scene scene = buildScene(p, builtinMesh("cylinder"), o);
    const Polylines& y = scene.yarns().curves;
    // Around the cylinder (u wraps) every course of the 4 x 2 rows closes into a loop, but those
    // whose loops reach over the open top or bottom rim, which are cut there.
    EXPECT_GE(scene.bindStats().closedLoops, 6u);
    for (size_t c = 0; c < y.curveCount(); ++c) {
        ASSERT_GE(y.size(c), 2u);
        for (uint32_t i = y.begin(c); i + 1 < y.end(c); ++i) {
            ASSERT_TRUE(std::isfinite(y.points[i].x) && std::isfinite(y.points[i].y) && std::isfinite(y.points[i].z));
            EXPECT_GT(glm::length(y.points[i + 1] - y.points[i]), 1e-9) << "degenerate segment in yarn " << c;
        }
    }
}

}  // namespace
}  // namespace knit
