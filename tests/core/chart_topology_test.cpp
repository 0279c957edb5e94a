// chartToCell: the crossing structure promised by knit/chart_topology.hpp, measured from the
// geometry (crossings.hpp), for every built-in chart.
#include <gtest/gtest.h>

#include "crossings.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"

namespace knit {
namespace {

void expectCrossingStructure(const std::string& name) {
    const ChartCell cell = chartToCell(builtinChart(name));
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << name;
}

TEST(ChartTopology, knitAndPurlChartsHaveTheCrossingStructureOfTheirStitches) {
    for (const std::string& name : builtinChartNames())
        if (name != "chart:cable4") expectCrossingStructure(name);
}

// Known gap: the cable loops' displaced heads are not yet threaded by the loops above (all four
// crossings come out in front). See docs/charts.md, "Status".
TEST(ChartTopology, DISABLED_cableLoopsAreThreadedThroughTheirSourceLoops) { expectCrossingStructure("chart:cable4"); }

TEST(ChartTopology, ribAlternatesFrontAndBackColumns) {
    const ChartCell cell = chartToCell(builtinChart("chart:rib1x1"));
    // The upper crossings of a knit column have the new loop in front, of a purl column behind.
    EXPECT_EQ(test::knitInFrontPurlBehind(cell, 1, 0, 1, 1), "");
}

TEST(ChartTopology, purlChartIsTheMirrorOfTheKnitChart) {
    const Pattern k = chartToCell(builtinChart("chart:stockinette")).pattern;
    const Pattern p = chartToCell(builtinChart("chart:reverse-stockinette")).pattern;
    ASSERT_EQ(k.points.size(), p.points.size());
    for (size_t i = 0; i < k.points.size(); ++i) {
        EXPECT_DOUBLE_EQ(k.points[i].x, p.points[i].x);
        EXPECT_NEAR(k.points[i].z, -p.points[i].z, 1e-12);
    }
}

TEST(ChartTopology, periodicEdgesCloseEachCourse) {
    const ChartCell cell = chartToCell(builtinChart("chart:garter"));
    EXPECT_EQ(cell.loops.size(), 4u);
    const PatternInfo info = describePattern(cell.pattern);
    EXPECT_EQ(info.loops1x1, 2u);  // one closed course per row on the torus
    EXPECT_EQ(info.crossings[0], 2u);
}

}  // namespace
}  // namespace knit
