#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <sstream>

#include "common/fixtures.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "common/test_paths.hpp"

namespace knit {
namespace {

std::string errorOf(const std::string& text) {
    std::istringstream in(text);
    try {
        parsePyp(in, "bad.pyp");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

const char* kTiny = R"(*pattern # px py radius n
1 1 0.1 3

*Q
0.1 0.5 0 0
0.5 0.5 0.1 0
0.9 0.5 0 0

*E
0 1 0 0
1 2 0 0
2 0 1 0
)";

TEST(Pattern, everySharedPatternLoads) {
    struct Expect {
        const char* file;
        double px, radius;
        size_t n;
    };
    const Expect expected[] = {{"stockinette.pyp", 0.0150513, 0.001, 100},
                               {"stockinette_small.pyp", 0.001476, 0.0001, 100},
                               {"stocktiny.pyp", 0.00144, 0.0002, 13},
                               {"stocktiniest.pyp", 0.00072, 0.0001, 13},
                               {"basket.pyp", 0.0107037, 0.001, 80},
                               {"satin.pyp", 0.0111111, 0.001, 130},
                               {"slip_stitch_honeycomb.pyp", 0.0109376, 0.001, 182}};
    for (const Expect& e : expected) {
        const Pattern p = loadPyp(test::sharedPattern(e.file));
        EXPECT_NEAR(p.px, e.px, 1e-7) << e.file;
        EXPECT_NEAR(p.radius, e.radius, 1e-6) << e.file;  // the table rounds
        EXPECT_EQ(p.points.size(), e.n) << e.file;
        EXPECT_EQ(p.edges.size(), e.n) << e.file;  // one outgoing edge per vertex
        EXPECT_TRUE(p.extraBlocks.count("RL")) << e.file;
    }
}

TEST(Pattern, stockinetteInfoCountsTwoCoursesPerCell) {
    const PatternInfo info = describePattern(loadPyp(test::sharedPattern("stockinette.pyp")));
    EXPECT_EQ(info.loops1x1, 2u);
    EXPECT_EQ(info.openYarns1x1, 0u);
    // Two courses cross the cell sideways: one edge leaves through +x (or -x) per course.
    EXPECT_EQ(info.crossings[0] + info.crossings[1], 2u);
}

TEST(Pattern, writeThenParseGivesSamePattern) {
    const Pattern p = loadPyp(test::sharedPattern("basket.pyp"));
    std::stringstream ss;
    writePyp(ss, p);
    const Pattern q = parsePyp(ss, "roundtrip");
    ASSERT_EQ(p.points.size(), q.points.size());
    for (size_t i = 0; i < p.points.size(); ++i) EXPECT_EQ(p.points[i], q.points[i]);
    EXPECT_EQ(p.twist, q.twist);
    EXPECT_EQ(p.edges, q.edges);
    EXPECT_EQ(p.extraBlocks, q.extraBlocks);
}

TEST(Pattern, tinyValidPatternParses) { EXPECT_EQ(errorOf(kTiny), ""); }

TEST(Pattern, missingEdgeBlockIsRejected) {
    std::string text(kTiny);
    text.resize(text.find("*E"));
    EXPECT_NE(errorOf(text).find("missing block *E"), std::string::npos) << errorOf(text);
}

TEST(Pattern, wrongVertexCountNamesTheBlock) {
    std::string text(kTiny);
    text.replace(text.find("1 1 0.1 3"), 9, "1 1 0.1 4");
    const std::string err = errorOf(text);
    EXPECT_NE(err.find("bad.pyp:"), std::string::npos) << err;
    EXPECT_NE(err.find("*Q has 3 rows"), std::string::npos) << err;
}

TEST(Pattern, nanCoordinateNamesTheLine) {
    std::string text(kTiny);
    text.replace(text.find("0.5 0.5 0.1 0"), 13, "0.5 nan 0.1 0");
    EXPECT_NE(errorOf(text).find("bad.pyp:6:"), std::string::npos) << errorOf(text);
    std::string inf(kTiny);
    inf.replace(inf.find("0.5 0.5 0.1 0"), 13, "0.5 inf 0.1 0");
    EXPECT_NE(errorOf(inf).find("not a finite number"), std::string::npos) << errorOf(inf);
}

TEST(Pattern, edgeToMissingVertexIsRejected) {
    std::string text(kTiny);
    text.replace(text.find("2 0 1 0"), 7, "2 7 1 0");
    EXPECT_NE(errorOf(text).find("missing vertex"), std::string::npos) << errorOf(text);
}

TEST(Pattern, diagonalOffsetIsRejected) {
    std::string text(kTiny);
    text.replace(text.find("2 0 1 0"), 7, "2 0 1 1");
    EXPECT_NE(errorOf(text).find("|dx|+|dy| > 1"), std::string::npos) << errorOf(text);
}

TEST(Pattern, thirdEdgeOnVertexIsRejected) {
    const std::string text = std::string(kTiny) + "0 2 0 0\n";
    EXPECT_NE(errorOf(text).find("third edge"), std::string::npos) << errorOf(text);
}

TEST(Pattern, garbageAndEmptyInputAreRejected) {
    EXPECT_NE(errorOf(""), "");
    EXPECT_NE(errorOf("hello world\n"), "");
    EXPECT_NE(errorOf("*pattern\n1 1 0.1 1e99\n"), "");
    EXPECT_NE(errorOf("*pattern\n1 1 -0.1 1\n*Q\n0 0 0 0\n*E\n"), "");
    std::string text(kTiny);
    text.resize(text.size() / 2);  // truncated
    EXPECT_NE(errorOf(text), "");
}

TEST(Pattern, missingFileAndDirectoryAreRejected) {
    EXPECT_THROW(loadPyp("/nonexistent/x.pyp"), Error);
    EXPECT_THROW(loadPyp(test::sharedDir()), Error);
}

TEST(Generator, stockinetteIsOneClosedCoursePerCell) {
    const Pattern p = generateStockinette();
    const PatternInfo info = describePattern(p);
    EXPECT_EQ(info.loops1x1, 1u);
    EXPECT_EQ(info.crossings[0], 1u);
    EXPECT_EQ(info.crossings[2] + info.crossings[3], 0u);
    EXPECT_NEAR(p.radius, 0.001, 1e-15);
    // The loop (height h) is taller than the row spacing, so neighbouring rows interlock.
    EXPECT_GT(info.boundsMax.y - info.boundsMin.y, p.py);
}

// The generator relaxes Crane's curve to the solver's tolerance; another compiler's round-off may
// stop it elsewhere within that (far below a micrometre here), so the comparison allows that.
TEST(Generator, shippedStockinetteIsWhatTheGeneratorMakes) {
    const Pattern shipped = loadPyp(std::string(test::sourceDir()) + "/patterns/stockinette.pyp");
    const Pattern made = generateStockinette();
    ASSERT_EQ(shipped.points.size(), made.points.size());
    for (size_t i = 0; i < made.points.size(); ++i)
        EXPECT_LT(glm::length(shipped.points[i] - made.points[i]), 1e-6) << "vertex " << i;
    EXPECT_EQ(shipped.edges, made.edges);
    EXPECT_EQ(shipped.px, made.px);
    EXPECT_EQ(shipped.py, made.py);
}

// *GAUGE: stitches and rows per period, written only when not 1 x 1 and read back; files
// without it are one stitch by one row per period.
TEST(Pattern, gaugeBlockRoundTripsAndDefaultsToOneStitchByOneRow) {
    std::istringstream tiny(kTiny);
    Pattern p = parsePyp(tiny, "tiny.pyp");
    EXPECT_EQ(p.stitchesPerPeriod, 1);
    EXPECT_EQ(p.rowsPerPeriod, 1);
    p.stitchesPerPeriod = 12;
    p.rowsPerPeriod = 16;
    std::stringstream text;
    writePyp(text, p);
    EXPECT_NE(text.str().find("*GAUGE"), std::string::npos);
    const Pattern back = parsePyp(text, "back.pyp");
    EXPECT_EQ(back.stitchesPerPeriod, 12);
    EXPECT_EQ(back.rowsPerPeriod, 16);
    EXPECT_EQ(back.extraBlocks.count("GAUGE"), 0u);
}

TEST(Pattern, badGaugeBlockFailsWithItsLine) {
    EXPECT_NE(errorOf(std::string(kTiny) + "*GAUGE\n0 2\n")
                  .find("bad.pyp:14: *GAUGE stitches and rows per period must be in 1 .. 1000000"),
              std::string::npos)
        << errorOf(std::string(kTiny) + "*GAUGE\n0 2\n");
    EXPECT_NE(errorOf(std::string(kTiny) + "*GAUGE\n3\n").find("*GAUGE row has 1 values, expected 2"),
              std::string::npos);
}

}  // namespace
}  // namespace knit
