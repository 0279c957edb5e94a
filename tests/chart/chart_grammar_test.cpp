// Chart grammar round 2 (issue 25): lace, slipped, tucked and twisted stitch tokens, the loops
// each consumes, row balance, anchoring and the colourwork line, with every error's position.
#include <gtest/gtest.h>

#include "knit/chart.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

std::string chartError(const std::string& text) {
    return test::errorOf([&] { parseChart(text, "bad.chart"); });
}

TEST(ChartGrammar, everyTokenIsOneColumnWithItsOperation) {
    const Chart c = parseChart("ktbl ptbl sl sl-wyif tuck k\nk2tog yo ssk yo k p\n", "t.chart");
    EXPECT_EQ(c.width, 6);
    EXPECT_EQ(c.opAt(0, 0), StitchOp::K2tog);
    EXPECT_EQ(c.opAt(0, 1), StitchOp::YarnOver);
    EXPECT_EQ(c.opAt(0, 2), StitchOp::Ssk);
    EXPECT_EQ(c.opAt(0, 5), StitchOp::Plain);
    EXPECT_EQ(c.at(0, 5), StitchKind::Purl);
    EXPECT_EQ(c.opAt(1, 0), StitchOp::ThroughBack);
    EXPECT_EQ(c.at(1, 0), StitchKind::Knit);
    EXPECT_EQ(c.opAt(1, 1), StitchOp::ThroughBack);
    EXPECT_EQ(c.at(1, 1), StitchKind::Purl);
    EXPECT_EQ(c.opAt(1, 2), StitchOp::Slip);
    EXPECT_EQ(c.opAt(1, 3), StitchOp::SlipFront);
    EXPECT_EQ(c.opAt(1, 4), StitchOp::Tuck);
    EXPECT_EQ(c.colourwork, Colourwork::Painted);
}

TEST(ChartGrammar, loopsAreConsumedLeftToRightTheTopOneFirst) {
    // `k yo k2tog k` over `k k k k`: k takes loop 0, yo none, k2tog loops 1 and 2 (1 on top), k 3.
    const Chart c = parseChart("k yo k2tog k\nk k k k\n", "t.chart");
    EXPECT_EQ(c.sources(1, 0), std::vector<int>({0}));
    EXPECT_TRUE(c.sources(1, 1).empty());
    EXPECT_EQ(c.sourceColumn(1, 1), -1);
    EXPECT_EQ(c.sources(1, 2), std::vector<int>({1, 2}));
    EXPECT_EQ(c.sources(1, 3), std::vector<int>({3}));
    EXPECT_EQ(parseChart("k ssk yo k\nk k k k\n", "t").sources(1, 1), std::vector<int>({2, 1}));
    EXPECT_EQ(parseChart("yo k3tog yo\nk k k\n", "t").sources(1, 1), std::vector<int>({0, 1, 2}));
    EXPECT_EQ(parseChart("yo sssk yo\nk k k\n", "t").sources(1, 1), std::vector<int>({2, 1, 0}));
    EXPECT_EQ(parseChart("yo cdd yo\nk k k\n", "t").sources(1, 1), std::vector<int>({1, 0, 2}));
    // A cable after a decrease starts where the decrease ended.
    const Chart cable = parseChart("k2tog yo c1/1f\nk k k k\n", "t");
    EXPECT_EQ(cable.sources(1, 2), std::vector<int>({3}));
    EXPECT_EQ(cable.sources(1, 3), std::vector<int>({2}));
    EXPECT_EQ(loopsConsumed(StitchOp::YarnOver), 0);
    EXPECT_EQ(loopsConsumed(StitchOp::Ssk), 2);
    EXPECT_EQ(loopsConsumed(StitchOp::Cdd), 3);
    EXPECT_EQ(loopsConsumed(StitchOp::Tuck), 1);
}

TEST(ChartGrammar, unbalancedRowNamesPositionAndBothCounts) {
    EXPECT_EQ(chartError("k yo k k\nk k k k\n"),
              "bad.chart:1:8: row consumes 3 loops but the row below makes 4 (yo takes none, k2tog and ssk two, "
              "k3tog, sssk and cdd three, every other stitch one): pair each yo with a decrease");
    // Too many: the token where the count goes over is named.
    EXPECT_NE(chartError("k k\nk2tog k\n").find("bad.chart:2:7: row consumes 3 loops but the row below makes 2"),
              std::string::npos);
    EXPECT_NE(chartError("k k k\nk3tog k k\n").find("bad.chart:2:7: row consumes 5 loops"), std::string::npos);
}

TEST(ChartGrammar, unknownTokenListsTheNewOnes) {
    EXPECT_EQ(chartError("k p2tog\n"),
              "bad.chart:1:3: unknown stitch 'p2tog' (expected k, p, yo, k2tog, ssk, k3tog, sssk, cdd, sl, sl-wyif, "
              "tuck, ktbl, ptbl or a cable c1/1f c1/1b c2/2f c2/2b c3/3f c3/3b)");
}

TEST(ChartGrammar, aColumnOfYarnOversIsRefusedSayingWhy) {
    EXPECT_EQ(chartError("k2tog yo\nk2tog yo\n"),
              "bad.chart:2:7: column 2 is a yarn-over on every row: its loops hang on nothing below, so the fabric "
              "splits into a ladder there (work it as a stitch on at least one row)");
    EXPECT_NO_THROW(parseChart("k k\nk2tog yo\n", "ok.chart"));
}

TEST(ChartGrammar, aLoopSlippedOnEveryRowIsRefusedSayingWhy) {
    EXPECT_EQ(chartError("k sl k\nk sl k\n"),
              "bad.chart:2:3: the loop in column 2 is slipped or tucked on every row: it is never worked, so the rows "
              "are not held together there");
    EXPECT_NE(chartError("k tuck\n").find("bad.chart:1:3: the loop in column 2 is slipped or tucked on every row"),
              std::string::npos);
    EXPECT_EQ(chartError("k k\nk sl\nk sl\nk sl\nk sl\nk k\n"),
              "bad.chart:2:3: the loop in column 2 is slipped or tucked on 4 rows in a row (at most 3): work it on a "
              "row in between");
    EXPECT_NO_THROW(parseChart("k k\nk sl\nk sl\nk sl\nk k\n", "ok.chart"));
}

TEST(ChartGrammar, colourworkLineAfterThePalette) {
    const char* body = "k k\nk k\n\nA B\nB A\nA=#ffffff B=#000000\n";
    EXPECT_EQ(parseChart(std::string(body) + "stranded\n", "t").colourwork, Colourwork::Stranded);
    EXPECT_EQ(parseChart("k k\nk k\n\nA B\nA B\nA=#ffffff B=#000000\nintarsia\n", "t").colourwork,
              Colourwork::Intarsia);
    EXPECT_EQ(parseChart(body, "t").colourwork, Colourwork::Painted);
    EXPECT_EQ(chartError("k k\nstranded\n"),
              "bad.chart:2:1: 'stranded' needs a colour block and a palette: it says how their colours are knitted");
    EXPECT_EQ(chartError("k k\n\nA B\nstranded\nA=#ffffff B=#000000\n"),
              "bad.chart:4:1: 'stranded' goes after the palette line (line 5)");
    EXPECT_EQ(chartError(std::string(body) + "stranded\nintarsia\n"),
              "bad.chart:8:1: a second colourwork line (the first is line 7)");
    EXPECT_EQ(chartError("k k k k k\n\nA B C D E\nA=#000000 B=#000001 C=#000002 D=#000003 E=#000004\nstranded\n"),
              "bad.chart:1:1: row uses 5 colours (ABCDE); stranded colourwork carries at most 4 yarns along a row");
}

}  // namespace
}  // namespace knit
