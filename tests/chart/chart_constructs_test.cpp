// Issue 25 constructs in the initial cell (chartToCell, before relaxation): the crossing
// structure knitting gives each token, measured from the geometry (crossings.hpp).
#include <gtest/gtest.h>

#include <cstdio>

#include "crossings.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"

namespace knit {
namespace {

using test::Crossing;

struct Range {
    uint32_t a = 0, b = 0;
};
Range rangeOf(const StitchLoop& l) { return {l.first, l.first + l.count}; }

// Crossings of the vertices of `a` with those of `b` moved by iy periods along y, sorted bottom to top.
std::vector<Crossing> between(const ChartCell& cell, Range a, Range b, int iy = 0) {
    std::vector<Crossing> c = test::crossingsBetween(cell.pattern, a.a, a.b, b.a, b.b, iy);
    std::sort(c.begin(), c.end(), [](const Crossing& x, const Crossing& y) { return x.at.y < y.at.y; });
    return c;
}

std::string describe(const std::vector<Crossing>& c) {
    std::string s;
    for (const Crossing& x : c) s += std::string(x.at.z > x.zb ? "F" : "B") + " ";
    return s;
}

// Every loop a stitch is pulled through is crossed four times: the feet of the new loop behind its
// legs (lower two), the legs of the new loop in front of its head (upper two) for knit; the
// mirror for purl. "" or what is wrong.
std::string checkThrough(const ChartCell& cell, const StitchLoop& l) {
    const std::string where = "stitch (" + std::to_string(l.row) + ", " + std::to_string(l.column) + ")";
    for (const LoopRef& ref : l.through) {
        const StitchLoop& b = cell.loop(ref.row, ref.column);
        // A loop taken is below: in the tile below when its row index is not smaller.
        const std::vector<Crossing> c = between(cell, rangeOf(l), rangeOf(b), ref.row >= l.row ? -1 : 0);
        const std::string with =
            where + " through (" + std::to_string(ref.row) + ", " + std::to_string(ref.column) + "): " + describe(c);
        if (c.size() != 4) return with + "expected 4 crossings";
        const bool knit = l.kind == StitchKind::Knit;
        for (size_t i = 0; i < 4; ++i)
            if ((c[i].at.z > c[i].zb) != ((i >= 2) == knit)) return with + "wrong over/under";
    }
    return "";
}

ChartCell cellOf(const std::string& text) { return chartToCell(parseChart(text, text)); }

void expectEveryStitchThreaded(const std::string& text) {
    const ChartCell cell = cellOf(text);
    EXPECT_GT(minYarnDistance(cell.pattern), 0.3) << text;  // the relaxation starts untangled
    for (const StitchLoop& l : cell.loops)
        if (l.madeLoop) EXPECT_EQ(checkThrough(cell, l), "") << text;
}

TEST(ChartConstructs, everyStitchIsPulledThroughTheLoopsItTakes) {
    for (const char* text :
         {"k k k k\nk yo k2tog k\nk k k k\n", "k k k k\nk ssk yo k\n", "k k k\nyo k3tog yo\nk k k\n",
          "k k k\nyo sssk yo\n", "k k k\nyo cdd yo\nk k k\n", "k k k\nk sl k\nk k k\n", "k k k\nk sl-wyif k\nk k k\n",
          "k k k\nk tuck k\nk k k\n", "k k k\nk ktbl k\n", "p p p\np ptbl p\nk k k\n", "k k\nk sl\nk sl\nk k\n",
          "p k p\np k p\np tuck p\n", "k k k k k k\nk k2tog yo c1/1f k\n"})
        expectEveryStitchThreaded(text);
}

TEST(ChartConstructs, decreasesTakeTheirLoopsTogetherTheTopOneInFront) {
    // k2tog: the left loop on top; ssk: the right; k3tog: left, centre, right from the front;
    // sssk the reverse; cdd: the centre, then the left, then the right.
    const struct {
        const char* text;
        int column;
        std::vector<int> order;  // the loops of row 0, front to back
    } cases[] = {{"k yo k2tog k\nk k k k\n", 2, {1, 2}},
                 {"k ssk yo k\nk k k k\n", 1, {2, 1}},
                 {"yo k3tog yo\nk k k\n", 1, {0, 1, 2}},
                 {"yo sssk yo\nk k k\n", 1, {2, 1, 0}},
                 {"yo cdd yo\nk k k\n", 1, {1, 0, 2}}};
    for (const auto& t : cases) {
        const ChartCell cell = cellOf(t.text);
        const StitchLoop& d = cell.loop(1, t.column);
        ASSERT_EQ(d.through.size(), t.order.size()) << t.text;
        for (size_t i = 0; i < t.order.size(); ++i) {
            EXPECT_EQ(d.through[i], (LoopRef{0, t.order[i]})) << t.text;
            EXPECT_EQ(cell.loop(0, t.order[i]).headShift, t.column - t.order[i]) << t.text;
        }
        // Each pair of the stack crosses, the higher one in front at every crossing.
        for (size_t i = 0; i < t.order.size(); ++i)
            for (size_t j = i + 1; j < t.order.size(); ++j) {
                const std::vector<Crossing> c =
                    between(cell, rangeOf(cell.loop(0, t.order[i])), rangeOf(cell.loop(0, t.order[j])));
                EXPECT_GE(c.size(), 1u) << t.text << " loops " << t.order[i] << ", " << t.order[j];
                for (const Crossing& x : c)
                    EXPECT_GT(x.at.z, x.zb) << t.text << " loop " << t.order[i] << " over " << t.order[j];
            }
    }
}

// A yarn-over is pulled through nothing: it never passes in front of a loop of the row below
// (that is how a stitch passes through a head); the knit stitch beside it does.
TEST(ChartConstructs, yarnOverIsPulledThroughNothing) {
    const ChartCell cell = cellOf("k k k k\nk yo k2tog k\nk k k k\n");
    const StitchLoop& yo = cell.loop(1, 1);
    EXPECT_TRUE(yo.through.empty());
    EXPECT_EQ(yo.sourceColumn, -1);
    for (int c = 0; c < cell.width; ++c)
        for (const Crossing& x : between(cell, rangeOf(yo), rangeOf(cell.loop(0, c))))
            EXPECT_LT(x.at.z, x.zb) << "the yo passes in front of loop (0, " << c << ")";
    // The knit stitch beside it does (checkThrough: its legs over the head below).
    EXPECT_EQ(checkThrough(cell, cell.loop(1, 0)), "");
    // The stitch above it is pulled through it like through any loop.
    EXPECT_EQ(cell.loop(2, 1).through, std::vector<LoopRef>({{1, 1}}));
}

// sl / sl-wyif: the course floats past the slipped loop behind / in front of it, and the loop
// spans two rows: the stitch above is pulled through it, its head as high as the row's heads.
void expectSlip(const char* text, bool front) {
    const ChartCell cell = cellOf(text);
    const StitchLoop& f = cell.loop(1, 1);
    EXPECT_FALSE(f.madeLoop);
    const StitchLoop& slipped = cell.loop(0, 1);
    EXPECT_EQ(slipped.lift, 1);
    const std::vector<Crossing> c = between(cell, rangeOf(f), rangeOf(slipped));
    EXPECT_EQ(c.size(), 2u) << text;  // one leg each
    for (const Crossing& x : c) EXPECT_EQ(x.at.z > x.zb, front) << text;
    EXPECT_EQ(cell.loop(2, 1).through, std::vector<LoopRef>({{0, 1}}));
    auto top = [&](const StitchLoop& l) {
        double y = -1e300;
        for (uint32_t i = l.first; i < l.first + l.count; ++i) y = std::max(y, cell.pattern.points[i].y);
        return y;
    };
    auto bottom = [&](const StitchLoop& l) {
        double y = 1e300;
        for (uint32_t i = l.first; i < l.first + l.count; ++i) y = std::min(y, cell.pattern.points[i].y);
        return y;
    };
    EXPECT_NEAR(top(slipped), top(cell.loop(1, 0)), 0.05 * cell.pattern.radius) << text;
    EXPECT_NEAR(bottom(slipped), bottom(cell.loop(0, 0)), 0.05 * cell.pattern.radius) << text;
    ASSERT_EQ(cell.floats.size(), 1u);
    EXPECT_EQ(cell.floats[0].row, 1);
    EXPECT_EQ(cell.floats[0].firstColumn, 1);
    EXPECT_EQ(cell.floats[0].columns, 1);
    EXPECT_EQ(cell.floats[0].front, front);
}

TEST(ChartConstructs, slippedStitchSpansTwoRowsWithTheYarnBehindOrInFront) {
    expectSlip("k k k\nk sl k\nk k k\n", false);
    expectSlip("k k k\nk sl-wyif k\nk k k\n", true);
}

// tuck: the tuck loop lies behind the held loop, through nothing; the stitch above is pulled
// through both, the held loop on top.
TEST(ChartConstructs, tuckLoopLiesBehindTheHeldLoopAndIsTakenWithIt) {
    const ChartCell cell = cellOf("k k k\nk tuck k\nk k k\n");
    const StitchLoop &tuck = cell.loop(1, 1), &heldLoop = cell.loop(0, 1);
    EXPECT_TRUE(tuck.madeLoop);
    EXPECT_TRUE(tuck.through.empty());
    EXPECT_EQ(heldLoop.lift, 1);
    EXPECT_EQ(cell.loop(2, 1).through, std::vector<LoopRef>({{0, 1}, {1, 1}}));
    const std::vector<Crossing> c = between(cell, rangeOf(tuck), rangeOf(heldLoop));
    EXPECT_GE(c.size(), 2u);
    for (const Crossing& x : c) EXPECT_LT(x.at.z, x.zb) << "the tuck loop passes in front of the held loop";
    for (int col = 0; col < cell.width; ++col)
        if (col != 1)
            for (const Crossing& x : between(cell, rangeOf(tuck), rangeOf(cell.loop(0, col))))
                EXPECT_LT(x.at.z, x.zb) << "the tuck loop passes through loop (0, " << col << ")";
    EXPECT_TRUE(cell.floats.empty());
}

// ktbl / ptbl: the loop's halves cross once, at its base: above the head of the loop below and
// below its own centre; the strand from the left foot (rising to the right leg) in front.
void expectTwisted(const char* text) {
    const ChartCell cell = cellOf(text);
    const StitchLoop& l = cell.loop(1, 1);
    const std::vector<Crossing> self = between(cell, rangeOf(l), rangeOf(l));
    // crossingsBetween sees each self-crossing from both segments.
    ASSERT_EQ(self.size(), 2u) << text;
    const Crossing& x = self[0].a < self[0].b ? self[0] : self[1];
    EXPECT_GT(x.at.z, x.zb) << text << ": the strand from the left foot is not in front";
    double centre = 0, headBelow = -1e300;
    for (uint32_t i = l.first; i < l.first + l.count; ++i) centre += cell.pattern.points[i].y / l.count;
    const StitchLoop& below = cell.loop(0, 1);
    for (uint32_t i = below.first; i < below.first + below.count; ++i)
        headBelow = std::max(headBelow, cell.pattern.points[i].y);
    EXPECT_LT(x.at.y, centre) << text;
    EXPECT_GT(x.at.y, headBelow) << text;
    // Untwisted stitches do not cross themselves.
    EXPECT_TRUE(between(cell, rangeOf(cell.loop(1, 0)), rangeOf(cell.loop(1, 0))).empty()) << text;
}

TEST(ChartConstructs, twistedStitchesCrossAtTheBase) {
    expectTwisted("k k k\nk ktbl k\nk k k\n");
    expectTwisted("p p p\np ptbl p\np p p\n");
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

const char* kStrandedBody =
    "k k k k\nk p k k\nk k k k\nk k k k\n\nA A A A\nA B A B\nB A B A\nA A A A\nA=#ff0000 B=#0000ff\n";

// Stranded colourwork: one yarn per colour a row uses, the same stitches as the chart knitted in
// one yarn per row (the same loops pulled through the same loops, the same colour per stitch);
// the vertices differ only near the feet beside another yarn's stitch (where the two yarns step
// apart, and the foot no longer blends into the neighbour's knit or purl) and in the floats,
// which pass behind every other yarn they cross.
TEST(ChartConstructs, strandedDiffersFromOneYarnOnlyInFloatsAndTheFeetAtColourChanges) {
    const ChartCell one = cellOf(kStrandedBody);
    const ChartCell two = cellOf(std::string(kStrandedBody) + "stranded\n");
    EXPECT_EQ(one.yarns, 4);
    EXPECT_EQ(two.yarns, 6);
    ASSERT_EQ(one.loops.size(), two.loops.size());
    EXPECT_EQ(one.colour, two.colour);
    const double r = one.pattern.radius;
    for (size_t k = 0; k < one.loops.size(); ++k) {
        const StitchLoop &a = one.loops[k], &b = two.loops[k];
        EXPECT_EQ(a.through, b.through);
        ASSERT_EQ(a.count, b.count);
        EXPECT_EQ(checkThrough(two, b), "");
        for (uint32_t i = 0; i < a.count; ++i) {
            const glm::dvec3 d = two.pattern.points[b.first + i] - one.pattern.points[a.first + i];
            const double t = -3.14159265358979 + 6.28318530717959 * i / a.count;
            EXPECT_LT(glm::length(d), (std::abs(t) < 3.14159265358979 - 0.8 ? 1e-12 : 2.0) * r)
                << "stitch " << a.row << "," << a.column << " vertex " << i;
            EXPECT_EQ(two.pattern.colour[b.first + i], one.pattern.colour[a.first + i]);
        }
    }
    // The floats: of the rows with two colours, each yarn floats past the other's stitches.
    EXPECT_TRUE(one.floats.empty());
    ASSERT_EQ(two.floats.size(), 8u);  // two rows, two yarns each passing two stitches of the other
    std::vector<bool> inLoop(two.pattern.points.size(), false);  // a stitch's vertex (not a float's)
    for (const StitchLoop& l : two.loops)
        for (uint32_t i = l.first; l.madeLoop && i < l.first + l.count; ++i) inLoop[i] = true;
    for (const ChartFloat& f : two.floats) {
        EXPECT_EQ(f.columns, 1);
        EXPECT_FALSE(f.front);
        int crossings = 0;
        for (uint32_t v : f.vertices)
            for (const Crossing& x :
                 test::crossingsBetween(two.pattern, v, v + 1, 0, uint32_t(two.pattern.points.size()), 0))
                if (inLoop[x.b] && std::abs(int(x.b) - int(v)) > 2) {
                    EXPECT_LT(x.at.z, x.zb) << "a float of row " << f.row << " passes in front";
                    ++crossings;
                }
        EXPECT_GT(crossings, 0);
    }
}

}  // namespace
}  // namespace knit
