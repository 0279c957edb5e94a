// chartToCell: the crossing structure promised by knit/chart_topology.hpp, measured from the
// geometry (crossings.hpp), for every built-in chart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "crossings.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"

namespace knit {
namespace {

void expectCrossingStructure(const std::string& name) {
    const ChartCell cell = chartToCell(builtinChart(name));
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << name;
}

TEST(ChartTopology, knitAndPurlChartsHaveTheCrossingStructureOfTheirStitches) {
    for (const std::string& name : builtinChartNames()) {
        const Chart chart = builtinChart(name);
        // Knit and purl only (the other constructs: chart_constructs_test.cpp).
        if (std::all_of(chart.op.begin(), chart.op.end(), [](StitchOp op) { return op == StitchOp::Plain; }))
            expectCrossingStructure(name);
    }
}

TEST(ChartTopology, cableLoopsAreThreadedThroughTheirSourceLoops) {
    expectCrossingStructure("chart:cable4");
    for (const char* text : {"k k k k\nc2/2b\n", "k k k k k k k k k k\nk c1/1f c3/3b k\n", "p k k p\np c1/1b p\n"}) {
        const ChartCell cell = chartToCell(parseChart(text, text));
        // Distinct yarns do not touch in the loose construction (the relaxation starts untangled).
        EXPECT_GT(minYarnDistance(cell.pattern), 0.3) << text;
        for (int r = 0; r < cell.height; ++r)
            for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << text;
    }
}

// The legs of a cable's loops (the row below the cable row) cross each other, the left-moving
// loop in front for a front cross, behind for a back cross.
void expectCableCross(const std::string& text, int leftMoving, int rightMoving, bool front, int samples = 24) {
    ChartCellOptions options;
    options.samplesPerStitch = samples;
    const ChartCell cell = chartToCell(parseChart(text, "t.chart"), options);
    const StitchLoop &l = cell.loop(cell.height - 1, leftMoving), &r = cell.loop(cell.height - 1, rightMoving);
    ASSERT_LT(l.headShift, 0);
    ASSERT_GT(r.headShift, 0);
    const std::vector<test::Crossing> c =
        test::crossingsBetween(cell.pattern, l.first, l.first + l.count, r.first, r.first + r.count, 0);
    EXPECT_EQ(c.size(), 4u) << text << " at " << samples;  // each leg of one loop over (under) each leg of the other
    for (const test::Crossing& x : c) {
        EXPECT_EQ(x.at.z > x.zb, front) << text << " at " << samples;
        // built well apart in depth where they cross (the relaxation starts untangled)
        EXPECT_GT(std::abs(x.at.z - x.zb), 0.5 * cell.pattern.radius) << text << " at " << samples;
    }
}

TEST(ChartTopology, cablesCrossInTheRequestedDirection) {
    expectCableCross("k k k k\nc2/2f\n", 2, 0, true);
    expectCableCross("k k k k\nc2/2b\n", 2, 0, false);
    expectCableCross("k k k k\nc2/2f\n", 3, 1, true);
    expectCableCross("p k k p\np c1/1b p\n", 2, 1, false);
    expectCableCross("p k k p\np c1/1f p\n", 2, 1, true);
}

// The cable legs cross between |t| = 1.5 and 1.66 of the loop parameter, narrower than the
// samples' spacing there: at 10 samples per stitch (the page's preview) both samples beside the
// crossing missed the cable depth, the 4 x 4 cable's legs were built 0.011 r apart and its
// preview relaxed them to 5e-11 r. At any sampling the legs are now built apart and cross as asked.
TEST(ChartTopology, cableLegsAreBuiltApartAtAnySampling) {
    for (int samples = 8; samples <= 16; ++samples) {
        expectCableCross("k k k k\nc2/2f\n", 2, 0, true, samples);
        expectCableCross("k k k k\nc2/2b\n", 3, 1, false, samples);
        expectCableCross("p k k p\np c1/1b p\n", 2, 1, false, samples);
        expectCableCross("k k k k k k\nc3/3f\n", 3, 0, true, samples);
        ChartCellOptions options;
        options.samplesPerStitch = samples;
        const ChartCell cell = chartToCell(parseChart("c2/2f\nk k k k\nk k k k\nk k k k\n", "cable"), options);
        EXPECT_GT(minYarnDistance(cell.pattern), 0.3) << samples;
    }
}

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
