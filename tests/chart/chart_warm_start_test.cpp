// The warm start's map from a coarse chart cell to a finer one (chart/chart_warm_start.hpp).
#include <gtest/gtest.h>

#include <cstdio>

#include <glm/geometric.hpp>

#include "chart/chart_warm_start.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"

namespace knit {
namespace {

ChartCell cellAt(const std::string& text, int samples) {
    ChartCellOptions o;
    o.samplesPerStitch = samples;
    return chartToCell(parseChart(text, "t.chart"), o);
}

// Carried unchanged (the coarse cell as its own "rest state"), the fine vertices land near where
// the fine cell has them; moved and scaled, they move and scale with it; another chart's cell is
// refused.
TEST(ChartWarmStart, theCoarseCellCarriesToTheFineOne) {
    for (const char* text : {"k p\np k\n", "c2/2f\nk k k k\nk k k k\nk k k k\n",
                             "k k\nk k\n\nA B\nA B\nA=#ff0000 "
                             "B=#0000ff\nstranded\n"}) {
        const Pattern coarse = cellAt(text, 10).pattern, fine = cellAt(text, 24).pattern;
        const std::optional<warmstart::FineStart> same = warmstart::carryRelaxed(coarse, coarse, fine);
        ASSERT_TRUE(same) << text;
        ASSERT_EQ(same->points.size(), fine.points.size());
        EXPECT_LT(same->mismatch, 4.0) << text;
        for (size_t i = 0; i < fine.points.size(); ++i)
            EXPECT_LE(glm::length(same->points[i] - fine.points[i]) / fine.radius, same->mismatch + 1e-9) << text;
        // The coarse cell moved by (1, 2, 3) r and its period doubled: each fine vertex follows.
        Pattern moved = coarse;
        moved.px *= 2;
        moved.py *= 2;
        for (glm::dvec3& p : moved.points) p = glm::dvec3(2 * p.x, 2 * p.y, p.z) + coarse.radius * glm::dvec3(1, 2, 3);
        const std::optional<warmstart::FineStart> carried = warmstart::carryRelaxed(coarse, moved, fine);
        ASSERT_TRUE(carried);
        EXPECT_EQ(carried->px, moved.px);
        for (size_t i = 0; i < fine.points.size(); ++i) {
            const glm::dvec3 expected = glm::dvec3(2 * same->points[i].x, 2 * same->points[i].y, same->points[i].z) +
                                        coarse.radius * glm::dvec3(1, 2, 3);
            EXPECT_LT(glm::length(carried->points[i] - expected), 1e-9) << text;
        }
    }
    // Every built-in chart carries within the warm start's tolerance (chart_pattern.cpp).
    for (const std::string& name : builtinChartNames()) {
        const Pattern coarse = cellAt(builtinChartText(name), 10).pattern,
                      fine = cellAt(builtinChartText(name), 24).pattern;
        const std::optional<warmstart::FineStart> same = warmstart::carryRelaxed(coarse, coarse, fine);
        ASSERT_TRUE(same) << name;
        std::printf("%-28s mismatch %.2f r\n", name.c_str(), same->mismatch);
        EXPECT_LT(same->mismatch, 4.0) << name;
    }
    EXPECT_FALSE(warmstart::carryRelaxed(cellAt("k\nk\n", 10).pattern, cellAt("k\nk\n", 10).pattern,
                                         cellAt("k\nk\nk\n", 24).pattern));
}

}  // namespace
}  // namespace knit
