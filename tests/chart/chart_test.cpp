// Chart parsing: the format, the built-in charts and every error naming line and column.
#include <gtest/gtest.h>

#include "knit/chart.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

std::string chartError(const std::string& text) {
    return test::errorOf([&] { parseChart(text, "bad.chart"); });
}

TEST(Chart, bottomRowIsTheLastLine) {
    const Chart c = parseChart("# comment\np p k\nk k k\n", "t.chart");
    EXPECT_EQ(c.width, 3);
    EXPECT_EQ(c.height, 2);
    EXPECT_EQ(c.at(0, 0), StitchKind::Knit);
    EXPECT_EQ(c.at(1, 0), StitchKind::Purl);
    EXPECT_EQ(c.at(1, 2), StitchKind::Knit);
}

TEST(Chart, cableSpansItsStitchesAndReordersThem) {
    const Chart c = parseChart("p k k k k p\np c2/2f p\n", "t.chart");
    EXPECT_EQ(c.width, 6);
    ASSERT_EQ(c.cables.size(), 1u);
    EXPECT_EQ(c.cables[0].row, 0);
    EXPECT_EQ(c.cables[0].column, 1);
    EXPECT_TRUE(c.cables[0].front);
    for (int col = 1; col < 5; ++col) EXPECT_EQ(c.at(0, col), StitchKind::Knit);
    // The two right-hand stitches move left: positions 1, 2 take the loops of columns 3, 4.
    EXPECT_EQ(c.sourceColumn(0, 1), 3);
    EXPECT_EQ(c.sourceColumn(0, 2), 4);
    EXPECT_EQ(c.sourceColumn(0, 3), 1);
    EXPECT_EQ(c.sourceColumn(0, 4), 2);
    EXPECT_EQ(c.sourceColumn(0, 0), 0);
    EXPECT_EQ(c.sourceColumn(1, 1), 1);
}

TEST(Chart, asymmetricAndBackCables) {
    const Chart c = parseChart("c1/1b c3/3f\n", "t.chart");
    EXPECT_EQ(c.width, 8);
    ASSERT_EQ(c.cables.size(), 2u);
    EXPECT_FALSE(c.cables[0].front);
    EXPECT_EQ(c.cables[1].column, 2);
    EXPECT_EQ(c.sourceColumn(0, 0), 1);
    EXPECT_EQ(c.sourceColumn(0, 2), 5);
}

TEST(Chart, colourBlockAndPalette) {
    const Chart c = parseChart("k k\nk k\n\nA B\nB B\nA=#f2e8d5 B=#1d3557\n", "t.chart");
    ASSERT_EQ(c.colour.size(), 4u);
    EXPECT_EQ(c.colour[2], 'A');  // row 1 (top line), column 0
    EXPECT_EQ(c.colour[0], 'B');
    EXPECT_EQ(c.palette.at('A')[0], 0xf2);
    EXPECT_EQ(c.palette.at('B')[2], 0x57);
}

TEST(Chart, everyBuiltinChartParses) {
    for (const std::string& name : builtinChartNames()) {
        const Chart c = builtinChart(name);
        EXPECT_GT(c.width, 0) << name;
        EXPECT_GT(c.height, 0) << name;
        EXPECT_EQ(name.rfind("chart:", 0), 0u) << name;
    }
    EXPECT_THROW(builtinChart("chart:nope"), Error);
}

TEST(Chart, raggedRowNamesLineAndColumn) {
    EXPECT_EQ(chartError("k k k\nk k\n"), "bad.chart:2:3: row has 2 stitches, expected 3 (as the first row, line 1)");
}

TEST(Chart, unknownTokenNamesLineAndColumn) {
    EXPECT_EQ(chartError("k k\nk  x\n"),
              "bad.chart:2:4: unknown stitch 'x' (expected k, p, yo, k2tog, ssk, k3tog, sssk, cdd, sl, sl-wyif, tuck, "
              "ktbl, ptbl or a cable c1/1f c1/1b c2/2f c2/2b c3/3f c3/3b)");
    EXPECT_NE(chartError("c4/4f\n").find("bad.chart:1:1: unknown stitch"), std::string::npos);
}

TEST(Chart, cableOverPurlIsRejected) {
    EXPECT_EQ(chartError("k k k k\nc2/2pf\n"),
              "bad.chart:2:1: cable 'c2/2pf' over purl stitches: the stitches a cable crosses are knit stitches");
}

TEST(Chart, cableWiderThanTheChart) {
    EXPECT_EQ(chartError("k k\n c2/2b\n"), "bad.chart:2:2: cable 'c2/2b' spans 4 stitches but the chart is 2 wide");
}

TEST(Chart, emptyChart) {
    EXPECT_EQ(chartError(""), "bad.chart:1:1: empty chart: no stitch rows");
    EXPECT_EQ(chartError("# only\n\n# comments\n"), "bad.chart:3:1: empty chart: no stitch rows");
}

TEST(Chart, badColourBlock) {
    EXPECT_EQ(chartError("k k\n\nA C\nA=#000000\n"), "bad.chart:3:3: colour 'C' is not in the palette");
    EXPECT_EQ(chartError("k k\n\nA A\nA=#00000g\n"), "bad.chart:4:1: palette entry 'A=#00000g' is not LETTER=#rrggbb");
    EXPECT_EQ(chartError("k k\nk k\n\nA A\nA=#000000\n"),
              "bad.chart:4:1: colour block has 1 rows, expected 2 (as the stitch block)");
    EXPECT_EQ(chartError("k\n\nA\n\nk\n"), "bad.chart:5:1: a chart has at most two blocks (stitches, then colours)");
}

}  // namespace
}  // namespace knit
