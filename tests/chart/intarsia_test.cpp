// Intarsia colourwork (issue 25): one yarn per colour area, knitted back and forth, the yarns'
// turns interlocked at the area boundaries (libknit/src/chart/chart_intarsia.hpp), before and
// after relaxation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>

#include "chart/crossings.hpp"
#include "chart/openings.hpp"
#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/chart_warnings.hpp"
#include "knit/chart_topology.hpp"
#include "knit/error.hpp"
#include "knit/relax.hpp"

namespace knit {
namespace {

// The Gauss linking integral of two polylines, exact per pair of segments (the solid angle formula
// of Klenin and Langowski, Biopolymers 54 (2000) 307). Closed (each polyline's last point joined to
// its first): the linking number. Open: the two arcs' mean linking number, the average over all
// directions of projection of half the signed crossings between them, which moves with the arcs
// continuously, as no closure of open arcs does.
double linking(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, bool closed = true) {
    auto unit = [](glm::dvec3 v) {
        const double l = glm::length(v);
        return l > 0 ? v / l : v;
    };
    auto asinClamped = [](double x) { return std::asin(std::clamp(x, -1.0, 1.0)); };
    double sum = 0;
    const size_t na = closed ? a.size() : a.size() - 1, nb = closed ? b.size() : b.size() - 1;
    for (size_t i = 0; i < na; ++i)
        for (size_t j = 0; j < nb; ++j) {
            const glm::dvec3 p1 = a[i], p2 = a[(i + 1) % a.size()], p3 = b[j], p4 = b[(j + 1) % b.size()];
            const glm::dvec3 r13 = p3 - p1, r14 = p4 - p1, r23 = p3 - p2, r24 = p4 - p2;
            const glm::dvec3 n1 = unit(glm::cross(r13, r14)), n2 = unit(glm::cross(r14, r24)),
                             n3 = unit(glm::cross(r24, r23)), n4 = unit(glm::cross(r23, r13));
            const double omega = asinClamped(glm::dot(n1, n2)) + asinClamped(glm::dot(n2, n3)) +
                                 asinClamped(glm::dot(n3, n4)) + asinClamped(glm::dot(n4, n1));
            const double s = glm::dot(glm::cross(p4 - p3, p2 - p1), r13);
            sum += s > 0 ? omega : (s < 0 ? -omega : 0.0);
        }
    return sum / (4 * M_PI);
}

// A yarn's turn between two rows: its vertices not in any stitch, with the feet either side
// (the last vertex of the row's last loop and the first of the next row's), the yarn's
// periodic offsets applied so it is one connected curve.
struct TurnCurve {
    int yarn = 0;
    std::vector<glm::dvec3> points;
    std::vector<uint32_t> vertices;  // the turn's own (not the feet)
    glm::dvec3 centre{0.0};
};
// An open yarn's tails (from a stitch to the yarn's end) are not turns.
std::vector<TurnCurve> turnsOf(const ChartCell& cell, const Pattern& p) {
    std::vector<const PeriodicEdge*> leaving(p.points.size(), nullptr);
    for (const PeriodicEdge& e : p.edges) leaving[e.v0] = &e;
    std::vector<bool> inStitch(p.points.size(), false);
    std::vector<int> yarnOf(p.points.size(), -1);
    for (const StitchLoop& l : cell.loops)
        for (uint32_t i = l.first; i < l.first + l.count; ++i) {
            inStitch[i] = true;
            yarnOf[i] = l.yarn;
        }
    std::vector<TurnCurve> turns;
    for (const PeriodicEdge& e : p.edges) {  // an edge from a stitch into a turn starts one
        if (!inStitch[e.v0] || inStitch[e.v1]) continue;
        TurnCurve t;
        t.yarn = yarnOf[e.v0];
        t.points.push_back(p.points[e.v0]);
        glm::dvec3 offset(e.dx * p.px, e.dy * p.py, 0);
        const PeriodicEdge* at = &e;
        while (at) {
            t.points.push_back(p.points[at->v1] + offset);
            t.vertices.push_back(at->v1);
            at = leaving[at->v1];
            if (!at) break;  // a tail: the yarn ends
            offset += glm::dvec3(at->dx * p.px, at->dy * p.py, 0);
            if (inStitch[at->v1]) break;
        }
        if (!at) continue;
        t.points.push_back(p.points[at->v1] + offset);
        for (const glm::dvec3& q : t.points) t.centre += q / double(t.points.size());
        turns.push_back(t);
    }
    return turns;
}

// How far a turn reaches in x.
double xExtent(const TurnCurve& t) {
    double lo = t.points.front().x, hi = lo;
    for (const glm::dvec3& q : t.points) {
        lo = std::min(lo, q.x);
        hi = std::max(hi, q.x);
    }
    return hi - lo;
}

// For every turn: how many turns of other yarns it is hooked through, and the smallest mean
// linking number (|linking(a, b, false)|) of a hooked pair and the largest of a free one.
//
// Measured on the open turns, closed by nothing. A turn is an open arc between two feet in the
// fabric, and a closure (the straight chord between the feet, then rays out in front of the work
// joined there) is another curve that relaxation moves: where two turns are carried six stitches
// on, the closures of two hooked turns crossed each other as their feet's depths changed: the
// linking numbers of the closed turns jumped three times while relaxing (1 to 0, 1 to 0, 0 to 1),
// each jump all in the closures' own term and none in the turns' (a yarn cannot pass through
// another: RelaxResult::closestApproach). The mean linking number of the open arcs has no closure to
// cross: over every built and relaxed cell of this file a hooked pair is at 0.54-0.92 and a free
// one at 0.00-0.17 (docs/charts.md, "Issue 25 round 10: long carries").
constexpr double kHooked = 0.35;                            // hooked above this
constexpr double kSurelyHooked = 0.45, kSurelyFree = 0.25;  // what the tests ask of the worst pairs
struct Interlock {
    std::vector<int> linkedWith;
    double worstUnlinked = 0, worstLinked = 1;
};
Interlock interlock(const ChartCell& cell, const Pattern& p) {
    const std::vector<TurnCurve> turns = turnsOf(cell, p);
    Interlock out;
    for (const TurnCurve& a : turns) {
        int linked = 0;
        for (const TurnCurve& b : turns) {
            if (b.yarn == a.yarn) continue;
            // b's image nearest to a, and the ones a period above and below it (a two-row cell
            // has one turn per yarn and boundary: the one above a turn and the one below are images)
            const glm::dvec3 d = a.centre - b.centre;
            for (int iy = -1; iy <= 1; ++iy) {
                const glm::dvec3 shift(std::round(d.x / p.px) * p.px, (std::round(d.y / p.py) + iy) * p.py, 0);
                std::vector<glm::dvec3> moved;
                for (const glm::dvec3& q : b.points) moved.push_back(q + shift);
                const double lk = std::abs(linking(a.points, moved, false));
                if (lk > kHooked) {
                    ++linked;
                    out.worstLinked = std::min(out.worstLinked, lk);
                } else {
                    out.worstUnlinked = std::max(out.worstUnlinked, lk);
                }
            }
        }
        out.linkedWith.push_back(linked);
    }
    return out;
}

// How a cell's anchored vertices lie on its turns: turns carried across a step (spanning more than
// three quarters of a stitch in x; a turn at a boundary that stays spans a third) and how many of
// them hold anchored vertices, turns that stay holding any, and anchored vertices on no turn.
struct HeldTurns {
    int carried = 0, carriedHeld = 0, keptHeld = 0;
    size_t offTurns = 0;
};
HeldTurns heldTurns(const ChartCell& cell) {
    const std::set<uint32_t> anchored(cell.anchors.begin(), cell.anchors.end());
    const double stitch = cell.pattern.px / cell.width;
    HeldTurns out;
    size_t onTurns = 0;
    for (const TurnCurve& t : turnsOf(cell, cell.pattern)) {
        const double extent = xExtent(t);
        const auto held = size_t(
            std::count_if(t.vertices.begin(), t.vertices.end(), [&](uint32_t v) { return anchored.count(v) > 0; }));
        onTurns += held;
        const bool carried = extent > 0.75 * stitch;
        out.carried += carried;
        out.carriedHeld += carried && held > 0;
        out.keptHeld += !carried && held > 0;
    }
    out.offTurns = anchored.size() - onTurns;
    return out;
}

// The columns beside a colour boundary.
std::vector<int> boundaryColumns(const Chart& chart) {
    std::vector<int> out;
    for (int c = 0; c < chart.width; ++c)
        if (chart.colourAt(0, c) != chart.colourAt(0, (c + 1) % chart.width) ||
            chart.colourAt(0, c) != chart.colourAt(0, (c + chart.width - 1) % chart.width))
            out.push_back(c);
    return out;
}

TEST(Intarsia, oneYarnPerAreaKnittedBackAndForth) {
    const Chart chart = builtinChart("chart:intarsia-blocks");
    const ChartCell cell = chartToCell(chart);
    ASSERT_EQ(cell.yarns, 2);
    EXPECT_TRUE(cell.floats.empty());
    // Each loop on its area's yarn (A: columns 0-1, B: 2-3), odd rows knitted back.
    for (const StitchLoop& l : cell.loops) {
        EXPECT_EQ(l.yarn, l.column < 2 ? 0 : 1) << l.row << ", " << l.column;
        EXPECT_EQ(l.reversed, l.row % 2 == 1);
    }
    // Two closed yarns, each climbing one period: the edges from a yarn's first vertex come back
    // to it after one period in y and none in x.
    std::set<uint32_t> seen;
    int chains = 0;
    for (uint32_t start = 0; start < cell.pattern.points.size(); ++start) {
        if (seen.count(start)) continue;
        ++chains;
        int dx = 0, dy = 0;
        uint32_t v = start;
        do {
            seen.insert(v);
            dx += cell.pattern.edges[v].dx;
            dy += cell.pattern.edges[v].dy;
            v = cell.pattern.edges[v].v1;
        } while (v != start);
        EXPECT_EQ(dx, 0);
        EXPECT_EQ(dy, 1);
    }
    EXPECT_EQ(chains, 2);
    // Each yarn keeps its colour: two colours, one per yarn.
    ASSERT_EQ(cell.pattern.colour.size(), cell.pattern.points.size());
    std::map<int, std::set<std::tuple<float, float, float>>> colours;
    for (const StitchLoop& l : cell.loops)
        for (uint32_t i = l.first; i < l.first + l.count; ++i)
            colours[l.yarn].insert({cell.pattern.colour[i].x, cell.pattern.colour[i].y, cell.pattern.colour[i].z});
    EXPECT_EQ(colours[0].size(), 1u);
    EXPECT_EQ(colours[1].size(), 1u);
    EXPECT_NE(*colours[0].begin(), *colours[1].begin());
    // The stitches are the plain stitches: legs over the head below, feet behind its legs.
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "");
}

TEST(Intarsia, oddChartsAreStackedTwiceAndAreasMayWrapRoundThePeriod) {
    // One row; the A area wraps round the period (columns 4, 0, 1).
    const ChartCell cell = chartToCell(parseChart("k k k k k\n\nA A B B A\nA=#ffffff B=#000000\nintarsia\n", "t"));
    EXPECT_EQ(cell.height, 2);
    EXPECT_EQ(cell.pattern.rowsPerPeriod, 2);
    EXPECT_EQ(cell.yarns, 2);
    const Interlock il = interlock(cell, cell.pattern);
    ASSERT_EQ(il.linkedWith.size(), 4u);  // each yarn turns once per row
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
}

// A slipped stitch inside an area floats as usual; a chart of odd height is stacked twice, and
// the cell lists the floats of its first copy only, at the chart's rows (the warnings index the
// chart's lines with them).
TEST(Intarsia, floatsInsideAnAreaAreListedOnceAtTheChartsRows) {
    const Chart chart = parseChart("k k k k k\nk sl sl k k\nk k k k k\n\nA A A A B\nA A A A B\nA A A A B\n"
                                   "A=#ffffff B=#000000\nintarsia\n",
                                   "float.chart");
    const ChartCell cell = chartToCell(chart);
    EXPECT_EQ(cell.height, 6);
    ASSERT_EQ(cell.floats.size(), 1u);
    EXPECT_EQ(cell.floats[0].row, 1);
    EXPECT_EQ(cell.floats[0].firstColumn, 1);
    EXPECT_EQ(cell.floats[0].columns, 2);
    EXPECT_FALSE(cell.floats[0].stranded);
    EXPECT_FALSE(cell.floats[0].front);
}

// Each turn is hooked through the neighbouring yarn's turns above and below it (a chain along
// the boundary), before and after relaxation; the relaxation keeps the yarns apart, the
// boundary stitches held by the stitches above them, and no hole opens at the boundary.
TEST(Intarsia, turnsInterlockAndTheBoundaryHoldsAfterRelaxation) {
    const Chart chart = builtinChart("chart:intarsia-blocks");
    const ChartPattern cp = relaxChart(chart);
    for (const Pattern* p : {&cp.cell.pattern, &cp.relaxed.pattern}) {
        const Interlock il = interlock(cp.cell, *p);
        ASSERT_EQ(il.linkedWith.size(), 4u);  // each of the 2 yarns turns once per row
        for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
        EXPECT_GT(il.worstLinked, kSurelyHooked);
        EXPECT_LT(il.worstUnlinked, kSurelyFree);
    }
    std::printf("intarsia-blocks: min distance %.3f r, closest approach %.3f r, %d iterations\n",
                cp.relaxed.minDistance, cp.relaxed.closestApproach, cp.relaxed.iterations);
    EXPECT_TRUE(cp.relaxed.converged);
    EXPECT_GE(cp.relaxed.minDistance, 1.9);
    EXPECT_GT(cp.relaxed.closestApproach, 0.2);
    ChartCell relaxed = cp.cell;
    relaxed.pattern = cp.relaxed.pattern;
    for (const int c : boundaryColumns(chart))
        for (int r = 0; r < relaxed.height; ++r) EXPECT_EQ(test::checkStitchEnds(relaxed, r, c), "");
    // No slit: the largest opening seen along z is no larger than plain knitting's.
    const double opening = test::largestOpening(cp.relaxed.pattern).radius;
    const double plain = test::largestOpening(relaxChart(builtinChart("chart:stockinette")).relaxed.pattern).radius;
    std::printf("intarsia-blocks: largest opening %.3f r (stockinette %.3f r)\n", opening, plain);
    EXPECT_LT(opening, plain + 0.25);
}

// Lace, twisted stitches and a cable across the boundary: the turns still hook into each other,
// and the loose construction keeps the yarns apart (the relaxation starts untangled).
TEST(Intarsia, turnsInterlockBesideLaceTwistedAndCabledStitches) {
    const ChartCell cell = chartToCell(parseChart("k k k k k k\nk c2/2f k\nk k k k k k\nk yo k2tog ktbl k k\n\n"
                                                  "A A A B B B\nA A A B B B\nA A A B B B\nA A A B B B\n"
                                                  "A=#ffffff B=#000000\nintarsia\n",
                                                  "mixed.chart"));
    const Interlock il = interlock(cell, cell.pattern);
    ASSERT_EQ(il.linkedWith.size(), 8u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_GT(minYarnDistance(cell.pattern), 0.3);
}

TEST(Intarsia, layoutsAPeriodicCellCannotKnitAreRefusedWithTheirPlace) {
    auto error = [](const std::string& text) {
        try {
            parseChart(text, "t.chart");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // A motif one row tall (its yarn could not turn round its neighbours'), named where the colour
    // block draws it, with what to do instead.
    const std::string motif = error("k k k\nk k k\n\nA B A\nA A A\nA=#ffffff B=#000000\nintarsia\n");
    EXPECT_NE(motif.find("t.chart:4:3: intarsia: the colour B area in row 2, column 2 lasts one row"),
              std::string::npos)
        << motif;
    EXPECT_NE(motif.find("knit it `stranded`"), std::string::npos) << motif;
    // A motif of 2 x 2 on a background is built (Intarsia.aMotif...).
    EXPECT_EQ(error("k k k k\nk k k k\nk k k k\nk k k k\n\nA A A A\nA B B A\nA B B A\nA A A A\n"
                    "A=#ffffff B=#000000\nintarsia\n"),
              "");
    // A boundary that steps one, two or three columns every row is knitted (the yarns carried
    // that many stitches on: Intarsia.aZigzag..., Intarsia.aBoundaryJumpingTwoColumns...,
    // Intarsia.aBoundaryJumpingThreeColumns...; refused before issue 25 round 9).
    EXPECT_EQ(error("k k k k\nk k k k\n\nA B B B\nA A B B\nA=#ffffff B=#000000\nintarsia\n"), "");
    EXPECT_EQ(error("k k k k k k\nk k k k k k\nk k k k k k\n\nA A A A B B\nA A A A B B\n"
                    "A A B B B B\nA=#ffffff B=#000000\nintarsia\n"),
              "");
    EXPECT_EQ(error("k k k k k k k\nk k k k k k k\nk k k k k k k\n\nA A A A A B B\nA A A A A B B\n"
                    "A A B B B B B\nA=#ffffff B=#000000\nintarsia\n"),
              "");
    // A motif row between two rows of one colour lasts one row: refused as above.
    const std::string row = error("k k k k k k k\nk k k k k k k\nk k k k k k k\n\nA A A A A A A\nA A A A A B B\n"
                                  "A A A A A A A\nA=#ffffff B=#000000\nintarsia\n");
    EXPECT_NE(row.find("t.chart:6:11: intarsia: the colour B area in row 2, columns 6-7 lasts one row: the areas "
                       "of the rows below and above do not continue into it"),
              std::string::npos)
        << row;
    // Stripes one stitch wide moving a column every row come back onto the other stripe of their
    // colour after the period: parsed, and stacked until each comes back to itself
    // (Intarsia.areasThatWanderOntoAnotherOfTheirColourAreStackedUntilEachComesBack).
    EXPECT_EQ(error("k k k k\nk k k k\n\nB A B A\nA B A B\nA=#ffffff B=#000000\nintarsia\n"), "");
    EXPECT_NE(error("k k\n\nA A\nA=#ffffff B=#000000\nintarsia\n").find("t.chart:1:1: intarsia needs at least two"),
              std::string::npos);
    // Purl beside the boundary: the turn leaves a knit foot from behind.
    EXPECT_NE(error("k p k k\nk k k k\n\nA A B B\nA A B B\nA=#ffffff B=#000000\nintarsia\n")
                  .find("t.chart:1:1: intarsia: the stitch in column 2 lies beside a colour boundary"),
              std::string::npos);
    // Purl inside an area is fine.
    EXPECT_EQ(error("k p k k k k\nk k k k k k\n\nA A A B B B\nA A A B B B\nA=#ffffff B=#000000\nintarsia\n"), "");
}

// The vertices of each yarn in order along it (an open yarn from its first end), and whether it is open.
struct YarnPath {
    std::vector<uint32_t> vertices;
    bool open = false;
};
std::vector<YarnPath> yarnPaths(const Pattern& p) {
    std::vector<int64_t> next(p.points.size(), -1);
    std::vector<bool> arrives(p.points.size(), false);
    for (const PeriodicEdge& e : p.edges) {
        next[e.v0] = e.v1;
        arrives[e.v1] = true;
    }
    std::vector<bool> seen(p.points.size(), false);
    std::vector<YarnPath> out;
    auto walk = [&](uint32_t start, bool open) {
        YarnPath y;
        y.open = open;
        for (int64_t v = start; v >= 0 && !seen[size_t(v)]; v = next[size_t(v)]) {
            seen[size_t(v)] = true;
            y.vertices.push_back(uint32_t(v));
        }
        out.push_back(y);
    };
    for (uint32_t v = 0; v < p.points.size(); ++v)
        if (!arrives[v]) walk(v, true);
    for (uint32_t v = 0; v < p.points.size(); ++v)
        if (!seen[v]) walk(v, false);
    return out;
}

// A motif (chart:intarsia-motif: 1 stitch by 3 rows on a background): the rows above and below
// are plain courses of the background's yarn; in the motif's rows the motif and the background
// beside it each have their own open yarn, knitted back and forth, which starts and ends in a tail
// behind the work; each yarn keeps its colour; along each of the motif's two boundaries the two
// yarns turn on alternate rows and the turns hook into each other.
TEST(Intarsia, aMotifIsKnittedByItsOwnOpenYarnInterlockedWithTheBackgrounds) {
    const Chart chart = builtinChart("chart:intarsia-motif");
    const ChartCell cell = chartToCell(chart);
    const Pattern& p = cell.pattern;
    EXPECT_EQ(cell.height, 5);  // not stacked: open yarns need no even row count
    ASSERT_EQ(cell.yarns, 4);   // rows 0 and 4, the motif, the background beside it
    const std::vector<YarnPath> paths = yarnPaths(p);
    ASSERT_EQ(paths.size(), 4u);
    int open = 0;
    for (const YarnPath& y : paths) open += y.open;
    EXPECT_EQ(open, 2);
    EXPECT_EQ(p.edges.size(), p.points.size() - 2);
    std::vector<int> yarnOfVertex(p.points.size(), -1);
    for (size_t k = 0; k < paths.size(); ++k)
        for (const uint32_t v : paths[k].vertices) yarnOfVertex[v] = int(k);
    // The stitch record: each loop's vertices on one yarn; the motif's loops (B) all on one open
    // yarn that holds no other loop, the background's rows 1-4 on the other open one.
    std::map<int, std::set<char>> lettersOfYarn;
    std::map<int, std::set<int>> rowsOfYarn;
    for (const StitchLoop& l : cell.loops) {
        const int y = yarnOfVertex[l.first];
        for (uint32_t i = l.first; i < l.first + l.count; ++i) ASSERT_EQ(yarnOfVertex[i], y);
        lettersOfYarn[y].insert(chart.colourAt(l.row, l.column));
        rowsOfYarn[y].insert(l.row);
        EXPECT_EQ(l.reversed, l.row == 2) << l.row << ", " << l.column;
    }
    for (const auto& [y, letters] : lettersOfYarn) {
        EXPECT_EQ(letters.size(), 1u) << "yarn " << y;
        EXPECT_EQ(rowsOfYarn[y].size(), paths[size_t(y)].open ? 3u : 1u) << "yarn " << y;
    }
    // Each vertex's colour is its yarn's: two colours in all, one per yarn.
    ASSERT_EQ(p.colour.size(), p.points.size());
    for (const YarnPath& y : paths)
        for (const uint32_t v : y.vertices) EXPECT_EQ(p.colour[v], p.colour[y.vertices.front()]);
    // The tails end behind the work (z below -2 r), a stitch or more from the boundary's feet.
    for (const YarnPath& y : paths) {
        if (!y.open) continue;
        for (const uint32_t v : {y.vertices.front(), y.vertices.back()}) EXPECT_LT(p.points[v].z / p.radius, -2.0);
    }
    // The turns: two along each boundary of the motif, one of each yarn, hooked into each other.
    const Interlock il = interlock(cell, p);
    ASSERT_EQ(il.linkedWith.size(), 4u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 1);
    EXPECT_GT(il.worstLinked, kSurelyHooked);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    // Knitting's crossings at every stitch, the motif's boundary stitches included.
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    EXPECT_GT(minYarnDistance(p), 0.3);
}

// A tail lies behind one stitch when the next one is slipped: at two it ran through the slipped
// stitch's float (the same depth behind the work), and the cell could not relax (distance 0).
TEST(Intarsia, aTailKeepsClearOfAFloatInItsRow) {
    const ChartCell cell =
        chartToCell(parseChart("k k k k k\nk k sl k k\nk k k k k\nk k k k k\n\nA A A A A\nA B B B A\nA B B B A\n"
                               "A A A A A\nA=#ffffff B=#000000\nintarsia\n",
                               "slip.chart"));
    ASSERT_EQ(cell.floats.size(), 1u);
    EXPECT_GT(minYarnDistance(cell.pattern), 0.3);
}

// Relaxed (open yarns, their tails anchored where they are woven in): converged, the yarns apart,
// the turns still hooked, every stitch held by the stitch above as knitting holds it (with only
// the tails' ends anchored the motif's first and last stitches lost a crossing with the head
// below), the tails still behind the work, and no hole at the boundary (free tails opened
// 2.26 r, an eyelet 1.6 r).
TEST(Intarsia, aMotifRelaxesWithItsBoundaryClosed) {
    const ChartPattern cp = relaxChart(builtinChart("chart:intarsia-motif"));
    const Pattern& p = cp.relaxed.pattern;
    std::printf("intarsia-motif: min distance %.3f r, closest approach %.3f r, %d iterations, converged %d\n",
                cp.relaxed.minDistance, cp.relaxed.closestApproach, cp.relaxed.iterations, int(cp.relaxed.converged));
    EXPECT_TRUE(cp.relaxed.converged);
    EXPECT_GE(cp.relaxed.minDistance, 1.9);
    EXPECT_GT(cp.relaxed.closestApproach, 0.2);
    const Interlock il = interlock(cp.cell, p);
    ASSERT_EQ(il.linkedWith.size(), 4u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 1);
    EXPECT_GT(il.worstLinked, kSurelyHooked);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    ChartCell relaxed = cp.cell;
    relaxed.pattern = p;
    for (int r = 0; r < relaxed.height; ++r)
        for (int c = 0; c < relaxed.width; ++c) EXPECT_EQ(test::checkStitchEnds(relaxed, r, c), "") << r << ", " << c;
    // The tails (the anchored vertices, the open yarns' two ends among them): behind the cell's
    // mean z.
    double zMean = 0;
    for (const glm::dvec3& q : p.points) zMean += q.z / double(p.points.size());
    const std::set<uint32_t> anchored(cp.cell.anchors.begin(), cp.cell.anchors.end());
    size_t ends = 0;
    for (const YarnPath& y : yarnPaths(p))
        if (y.open)
            for (const uint32_t v : {y.vertices.front(), y.vertices.back()}) {
                ends += anchored.count(v);
                EXPECT_LT((p.points[v].z - zMean) / p.radius, -1.5) << v;
            }
    EXPECT_EQ(ends, 4u);
    for (const uint32_t v : cp.cell.anchors) EXPECT_LT((p.points[v].z - zMean) / p.radius, -0.5) << v;
    const double opening = test::largestOpening(p).radius;
    const double plain = test::largestOpening(relaxChart(builtinChart("chart:stockinette")).relaxed.pattern).radius;
    std::printf("intarsia-motif: largest opening %.3f r (stockinette %.3f r)\n", opening, plain);
    EXPECT_LT(opening, plain + 0.25);
}

// The x (the pattern's frame, metres) of the boundary beside column c on its right (side +1) or
// left (-1): half a stitch over from the loop's centre.
double boundaryBeside(const Pattern& p, int width, int c, int side) { return p.px / width * (c + 0.5 * side); }
double periodicGap(double a, double b, double period) {
    const double d = std::fmod(std::abs(a - b), period);
    return std::min(d, period - d);
}

// chart:intarsia-diamond: each of the diamond's boundaries moves a column every row. Its rows are
// knitted by two open yarns (the diamond's, the background's beside it), each carried one stitch
// on between rows; every turn leaves its row's last stitch at that row's boundary and reaches the
// next row's first stitch at the next row's boundary, one column over.
TEST(Intarsia, aDiagonalsTurnSitsOnEachRowAtThatRowsBoundaryColumn) {
    const Chart chart = builtinChart("chart:intarsia-diamond");
    const ChartCell cell = chartToCell(chart);
    const Pattern& p = cell.pattern;
    ASSERT_EQ(cell.height, 5);
    ASSERT_EQ(cell.yarns, 4);  // rows 0 and 4, the diamond's, the background's in rows 1-3
    const std::vector<YarnPath> paths = yarnPaths(p);
    ASSERT_EQ(paths.size(), 4u);
    std::vector<int> yarnOfVertex(p.points.size(), -1);
    for (size_t k = 0; k < paths.size(); ++k)
        for (const uint32_t v : paths[k].vertices) yarnOfVertex[v] = int(k);
    // The diamond's 1 + 3 + 1 stitches on one open yarn, its rows knitted right, left, right.
    std::map<int, std::map<int, int>> stitchesOfYarnRow;
    for (const StitchLoop& l : cell.loops) {
        ++stitchesOfYarnRow[yarnOfVertex[l.first]][l.row];
        if (chart.colourAt(l.row, l.column) == 'B') {
            EXPECT_TRUE(paths[size_t(yarnOfVertex[l.first])].open);
            EXPECT_EQ(l.reversed, l.row == 2) << l.row << ", " << l.column;
        }
    }
    // Each yarn keeps its colour (one per yarn, as the export then gives each yarn:
    // ChartCommand.intarsiaMotifYarnsKeepTheirColourThroughTheExport for the path from here on).
    ASSERT_EQ(p.colour.size(), p.points.size());
    for (const YarnPath& y : paths)
        for (const uint32_t v : y.vertices) EXPECT_EQ(p.colour[v], p.colour[y.vertices.front()]);
    const int diamond = yarnOfVertex[cell.loop(1, 2).first];
    EXPECT_EQ(stitchesOfYarnRow[diamond], (std::map<int, int>{{1, 1}, {2, 3}, {3, 1}}));
    const int background = yarnOfVertex[cell.loop(1, 0).first];
    EXPECT_NE(p.colour[paths[size_t(diamond)].vertices.front()], p.colour[paths[size_t(background)].vertices.front()]);
    EXPECT_EQ(stitchesOfYarnRow[background], (std::map<int, int>{{1, 4}, {2, 2}, {3, 4}}));
    // Each turn: below its first foot at the lower row's boundary, above its last foot at the
    // upper row's, a column (one stitch) apart; within the inset and reach of the boundary.
    std::vector<int> loopOfVertex(p.points.size(), -1);
    for (size_t k = 0; k < cell.loops.size(); ++k)
        for (uint32_t i = cell.loops[k].first; i < cell.loops[k].first + cell.loops[k].count; ++i)
            loopOfVertex[i] = int(k);
    std::vector<const PeriodicEdge*> leaving(p.points.size(), nullptr);
    for (const PeriodicEdge& e : p.edges) leaving[e.v0] = &e;
    const double stitch = p.px / chart.width, unit = p.radius / 0.8;  // model units
    int turns = 0;
    for (const PeriodicEdge& e : p.edges) {
        if (loopOfVertex[e.v0] < 0 || loopOfVertex[e.v1] >= 0) continue;
        const StitchLoop& from = cell.loops[size_t(loopOfVertex[e.v0])];
        std::vector<glm::dvec3> turn;
        glm::dvec3 offset(e.dx * p.px, e.dy * p.py, 0);
        uint32_t v = e.v1;
        for (turn.push_back(p.points[v] + offset); loopOfVertex[v] < 0 && leaving[v];) {  // to a stitch or the end
            offset += glm::dvec3(leaving[v]->dx * p.px, leaving[v]->dy * p.py, 0);
            v = leaving[v]->v1;
            turn.push_back(p.points[v] + offset);
        }
        if (loopOfVertex[v] < 0) continue;  // an end tail, not a turn
        const StitchLoop& to = cell.loops[size_t(loopOfVertex[v])];
        ASSERT_EQ(to.row, from.row + 1);
        // A row knitted to the right turns at its right end, the next row starts there.
        const int side = from.reversed ? -1 : 1;
        EXPECT_NE(chart.colourAt(from.row, (from.column + side + chart.width) % chart.width),
                  chart.colourAt(from.row, from.column));
        EXPECT_NE(chart.colourAt(to.row, (to.column + side + chart.width) % chart.width),
                  chart.colourAt(to.row, to.column));
        const double below = boundaryBeside(p, chart.width, from.column, side),
                     above = boundaryBeside(p, chart.width, to.column, side);
        EXPECT_NEAR(periodicGap(below, above, p.px), stitch, 1e-9) << "turn from row " << from.row;
        const double footLow = p.points[e.v0].y, footHigh = turn.back().y;
        for (const glm::dvec3& q : turn) {
            if (q.y < footLow) EXPECT_LT(periodicGap(q.x, below, p.px), 1.25 * unit) << from.row;
            if (q.y > footHigh) EXPECT_LT(periodicGap(q.x, above, p.px), 1.25 * unit) << from.row;
        }
        ++turns;
    }
    EXPECT_EQ(turns, 4);  // two per boundary: rows 1-2 and 2-3
}

// The crossing structure at a diagonal step: along each boundary the two yarns still turn on
// alternate rows, each carried turn hooked (Gauss linking number +-1) through the other yarn's
// turn beside it and linked with no other turn, before and after relaxation; relaxed, the yarns
// keep apart, no hole opens at the steps and every stitch keeps knitting's crossings, the
// diamond's two tips (a one-stitch row between a tail and a carried turn) included: their tails
// lie behind their own legs at the row's loop centres, above the head of the loop below, which a
// tail lower down pushed out through the tip (docs/charts.md, "Diagonals").
TEST(Intarsia, aDiagonalsCarriedTurnsHookThroughTheNeighboursAndTheBoundaryStaysClosed) {
    const ChartPattern cp = relaxChart(builtinChart("chart:intarsia-diamond"));
    std::printf("intarsia-diamond: min distance %.3f r, closest approach %.3f r, %d iterations, converged %d\n",
                cp.relaxed.minDistance, cp.relaxed.closestApproach, cp.relaxed.iterations, int(cp.relaxed.converged));
    for (const Pattern* p : {&cp.cell.pattern, &cp.relaxed.pattern}) {
        const Interlock il = interlock(cp.cell, *p);
        ASSERT_EQ(il.linkedWith.size(), 4u);
        for (const int n : il.linkedWith) EXPECT_EQ(n, 1);
        EXPECT_GT(il.worstLinked, kSurelyHooked);
        EXPECT_LT(il.worstUnlinked, kSurelyFree);
    }
    for (int r = 0; r < cp.cell.height; ++r)
        for (int c = 0; c < cp.cell.width; ++c) EXPECT_EQ(test::checkStitch(cp.cell, r, c), "") << r << ", " << c;
    EXPECT_TRUE(cp.relaxed.converged);
    EXPECT_GE(cp.relaxed.minDistance, 1.9);
    EXPECT_GT(cp.relaxed.closestApproach, 0.2);
    ChartCell relaxed = cp.cell;
    relaxed.pattern = cp.relaxed.pattern;
    for (int r = 0; r < relaxed.height; ++r)  // the two tips (column 2, rows 1 and 3) included
        for (int c = 0; c < relaxed.width; ++c) EXPECT_EQ(test::checkStitchEnds(relaxed, r, c), "") << r << ", " << c;
    const double opening = test::largestOpening(cp.relaxed.pattern).radius;
    const double plain = test::largestOpening(relaxChart(builtinChart("chart:stockinette")).relaxed.pattern).radius;
    std::printf("intarsia-diamond: largest opening %.3f r (stockinette %.3f r)\n", opening, plain);
    EXPECT_LT(opening, plain + 0.25);
}

// A zigzag boundary (a column over every other row) continues from every row into the next, round
// the period: each area's yarn is one closed serpentine, carried a stitch on at each step, and
// every turn hooks through the other yarn's turns above and below.
TEST(Intarsia, aZigzagBoundaryIsKnittedByClosedCarriedYarns) {
    const ChartCell cell =
        chartToCell(parseChart("k k k k\nk k k k\n\nA B B B\nA A B B\nA=#ffffff B=#000000\nintarsia\n", "t"));
    EXPECT_EQ(cell.yarns, 2);
    EXPECT_TRUE(cell.anchors.empty());  // no tails, and a turn carried one stitch on is free
    for (const YarnPath& y : yarnPaths(cell.pattern)) EXPECT_FALSE(y.open);
    const Interlock il = interlock(cell, cell.pattern);
    ASSERT_EQ(il.linkedWith.size(), 4u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    EXPECT_GT(minYarnDistance(cell.pattern), 0.3);
}

// A two-row zigzag on a `width`-stitch repeat: the top row `a1` stitches of A then B, the bottom
// row `a0` of A then B (its boundary moving a1 - a0 columns between the rows, the other staying).
Chart zigzagChart(int width, int a1, int a0, const std::string& name) {
    const auto run = [](const char* token, int count) {  // `count` copies of `token`, space-separated
        std::string out;
        for (int i = 0; i < count; ++i) out += std::string(i ? " " : "") + token;
        return out;
    };
    const std::string stitches = run("k", width) + "\n";
    return parseChart(stitches + stitches + "\n" + run("A", a1) + " " + run("B", width - a1) + "\n" + run("A", a0) +
                          " " + run("B", width - a0) + "\nA=#ffffff B=#000000\nintarsia\n",
                      name);
}

// A two-row zigzag of two yarns (`cell` built from `chart`) relaxes: converged, >= 1.9 r, its four
// turns each hooked through the other yarn's turns above and below before and after, and every
// stitch keeping knitting's crossings with the head below. The relaxation in `out` if given.
void expectZigzagRelaxesHooked(const Chart& chart, const ChartCell& cell, const char* label,
                               ChartPattern* out = nullptr) {
    const ChartPattern cp = relaxChart(chart);
    if (out) *out = cp;
    std::printf("%s: min distance %.3f r, closest approach %.3f r, %d iterations, converged %d\n", label,
                cp.relaxed.minDistance, cp.relaxed.closestApproach, cp.relaxed.iterations, int(cp.relaxed.converged));
    for (const Pattern* p : {&cell.pattern, &cp.relaxed.pattern}) {
        const Interlock il = interlock(cell, *p);
        ASSERT_EQ(il.linkedWith.size(), 4u);
        for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
        EXPECT_GT(il.worstLinked, kSurelyHooked);
        EXPECT_LT(il.worstUnlinked, kSurelyFree);
    }
    EXPECT_TRUE(cp.relaxed.converged);
    EXPECT_GE(cp.relaxed.minDistance, 1.9);
    EXPECT_GT(cp.relaxed.closestApproach, 0.2);
    ChartCell relaxed = cp.cell;
    relaxed.pattern = cp.relaxed.pattern;
    for (int r = 0; r < relaxed.height; ++r)
        for (int c = 0; c < relaxed.width; ++c) EXPECT_EQ(test::checkStitchEnds(relaxed, r, c), "") << r << ", " << c;
}

// parseChart's error message for `text` ("" when it parses).
std::string parseError(const std::string& text) {
    try {
        parseChart(text, "t.chart");
    } catch (const Error& e) {
        return std::string(e.what());
    }
    return std::string();
}

// A boundary jumping two columns between rows (`A A A A B B` over `A A B B B B`): each area's yarn
// knits two stitches more or fewer on the next row, carried two stitches on behind the work. The
// yarns are closed serpentines, each turn sits at its own row's boundary below its first foot and
// at the next row's above its last (two stitches apart) and hooks through the other yarn's turns
// above and below; relaxed, every stitch keeps knitting's crossings and the boundary holds.
TEST(Intarsia, aBoundaryJumpingTwoColumnsIsCarriedTwoStitchesOn) {
    const Chart chart = parseChart("k k k k k k\nk k k k k k\n\nA A A A B B\nA A B B B B\nA=#ffffff B=#000000\n"
                                   "intarsia\n",
                                   "steep.chart");
    const ChartCell cell = chartToCell(chart);
    EXPECT_EQ(cell.yarns, 2);
    const HeldTurns held = heldTurns(cell);  // no tails: only the carried turns' crossovers are held
    EXPECT_EQ(held.carriedHeld, 2);
    EXPECT_EQ(held.keptHeld, 0);
    EXPECT_EQ(held.offTurns, 0u);
    for (const YarnPath& y : yarnPaths(cell.pattern)) EXPECT_FALSE(y.open);
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    // The two turns at the moving boundary reach across the two stitches (their x extent spans
    // more than two stitches); the two at the boundary that stays (round the period's edge), less
    // than one.
    const std::vector<TurnCurve> turns = turnsOf(cell, cell.pattern);
    ASSERT_EQ(turns.size(), 4u);
    const double stitch = cell.pattern.px / chart.width;
    int carried = 0, kept = 0;
    for (const TurnCurve& t : turns) {
        const double extent = xExtent(t);
        carried += extent > 2 * stitch;
        kept += extent < stitch;
    }
    EXPECT_EQ(carried, 2);
    EXPECT_EQ(kept, 2);
    expectZigzagRelaxesHooked(chart, cell, "steep zigzag");
}

// A boundary jumping three columns (issue 25 round 9) is knitted like one jumping two: the area's
// yarn carried three stitches on behind the work, its crossover held on the back of the stitches it
// passes, each turn still hooked through the other yarn's turns above and below. The carry is a
// float of the row it reaches (ChartFloat::carried), warned about beyond the float limit.
TEST(Intarsia, aBoundaryJumpingThreeColumnsIsCarriedThreeStitchesOn) {
    const Chart chart = parseChart("k k k k k k k\nk k k k k k k\nk k k k k k k\n\nA A B B B B B\nA A A A A B B\n"
                                   "A A A A A B B\nA=#ffffff B=#000000\nintarsia\n",
                                   "jump.chart");
    const ChartCell cell = chartToCell(chart);  // three rows: stacked twice
    EXPECT_EQ(cell.yarns, 2);
    EXPECT_EQ(cell.height, 6);
    for (const YarnPath& y : yarnPaths(cell.pattern)) EXPECT_FALSE(y.open);
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    // Four of the twelve turns are carried (rows 2 to 3 and 3 to 1, twice over), each reaching
    // across more than three stitches and held there; the eight at the boundaries that stay, free.
    const HeldTurns held = heldTurns(cell);
    EXPECT_EQ(held.carried, 4);
    EXPECT_EQ(held.carriedHeld, 4);
    EXPECT_EQ(held.keptHeld, 0);
    EXPECT_EQ(held.offTurns, 0u);
    const double stitch = cell.pattern.px / chart.width;
    int wide = 0;
    for (const TurnCurve& t : turnsOf(cell, cell.pattern)) {
        const double extent = xExtent(t);
        wide += extent > 3 * stitch;
    }
    EXPECT_EQ(wide, 4);
    const Interlock il = interlock(cell, cell.pattern);
    ASSERT_EQ(il.linkedWith.size(), 12u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_GT(il.worstLinked, kSurelyHooked);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    // The carries of the chart's rows, each three stitches behind columns 3-5 of the row it reaches.
    ASSERT_EQ(cell.floats.size(), 2u);
    for (const ChartFloat& f : cell.floats) {
        EXPECT_TRUE(f.carried);
        EXPECT_FALSE(f.stranded);
        EXPECT_EQ(f.firstColumn, 2);
        EXPECT_EQ(f.columns, 3);
        EXPECT_FALSE(f.vertices.empty());
    }
    EXPECT_EQ(cell.floats[0].row, 0);
    EXPECT_EQ(cell.floats[1].row, 2);
    EXPECT_TRUE(chartWarnings(chart, cell, 5).empty());
    const std::vector<ChartWarning> warned = chartWarnings(chart, cell, 2);
    ASSERT_EQ(warned.size(), 2u);
    EXPECT_EQ(warned[1].line, 1);  // the top row's stitch line
    EXPECT_EQ(warned[1].text,
              "row 3: the yarn of colour B carried up from the row below to its moved boundary over columns 3-5 is 3 "
              "stitches long, longer than the float limit of 2 stitches (long floats snag: catch it or move the "
              "boundary by fewer columns a row)");
}

// The steep zigzag three columns a row relaxes (1.8 s) with its turns still hooked and every
// stitch keeping knitting's crossings with the head below.
TEST(Intarsia, aZigzagThreeColumnsARowRelaxesWithItsCarriedTurnsHooked) {
    const Chart chart = parseChart("k k k k k k k k\nk k k k k k k k\n\nA A B B B B B B\nA A A A A B B B\n"
                                   "A=#ffffff B=#000000\nintarsia\n",
                                   "steep3.chart");
    const ChartCell cell = chartToCell(chart);
    EXPECT_EQ(heldTurns(cell).carriedHeld, 2);
    expectZigzagRelaxesHooked(chart, cell, "three-column zigzag");
}

// A boundary jumping six columns every row on a 24-stitch repeat (1286 cell vertices): the yarn
// carried six stitches on. Such a cell is past the preconditioned relaxation's old 1000-vertex
// limit, where plain L-BFGS stopped at the iteration cap; preconditioned it converges with every
// turn hooked and every stitch keeping knitting's crossings (issue 25 round 10).
TEST(Intarsia, aLargeCellCarriedSixStitchesOnRelaxesWithItsTurnsHooked) {
    const Chart chart = zigzagChart(24, 12, 6, "carry6.chart");
    const ChartCell cell = chartToCell(chart);
    EXPECT_GT(cell.pattern.points.size(), 1000u);
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    EXPECT_EQ(heldTurns(cell).carriedHeld, 2);
    expectZigzagRelaxesHooked(chart, cell, "six-column zigzag");
}

// A boundary moving six columns on a 20-stitch repeat (issue 25 round 10): relaxed, each turn is
// still hooked through the other yarn's turns above and below. Counted as before, with each turn
// closed out in front of the work, the two carried turns came out hooked once each: their
// closures had crossed each other three times while relaxing (all of each jump in the closures'
// term of the linking number, none in the turns'; closest approach 0.961 r), which the open arcs'
// mean linking number has no closure to do (interlock). And the count does fail: a turn drawn
// out of its hook, to the front of the work, is hooked through nothing.
TEST(Intarsia, aBoundaryMovingSixColumnsOnATwentyStitchRepeatRelaxesWithItsTurnsHooked) {
    const Chart chart = zigzagChart(20, 10, 4, "carry6on20.chart");
    const ChartCell cell = chartToCell(chart);
    ChartPattern cp;
    expectZigzagRelaxesHooked(chart, cell, "six-column zigzag on 20", &cp);
    for (const Pattern* p : {&cell.pattern, static_cast<const Pattern*>(&cp.relaxed.pattern)}) {
        const std::vector<TurnCurve> turns = turnsOf(cell, *p);
        ASSERT_EQ(turns.size(), 4u);
        // The carried turn of the first yarn, its own vertices mirrored to the front of its feet.
        const auto carried = std::max_element(turns.begin(), turns.end(), [](const TurnCurve& a, const TurnCurve& b) {
            return xExtent(a) + (a.yarn == 0) * 1e9 < xExtent(b) + (b.yarn == 0) * 1e9;
        });
        ASSERT_EQ(carried->yarn, 0);
        const double front = std::max(carried->points.front().z, carried->points.back().z);
        Pattern unhooked = *p;
        for (const uint32_t v : carried->vertices) unhooked.points[v].z = 2 * front - unhooked.points[v].z;
        const Interlock il = interlock(cell, unhooked);
        const size_t k = size_t(carried - turns.begin());
        std::printf("turn %zu drawn out of its hook: hooked through %d turns (largest free pair %.3f)\n", k,
                    il.linkedWith[k], il.worstUnlinked);
        EXPECT_EQ(il.linkedWith[k], 0);
    }
}

// Boundaries moving five columns on a 22-stitch repeat and ten on a 24-stitch one (issue 25 round
// 10): relaxed, the yarn's side bulges out in front of the work between the carried float behind
// it and the boundary that stays, where its edge stands at right angles to the work (its first
// stitch of the top row, (1, W - 1), faces along x: its own normal (0.999, -0.028, -0.021) for
// W = 22). Seen along that normal, the images of the loop below one period along x lie one period
// behind it but on top of it in the projection, and checkStitchEnds counted crossings with the one
// a period away; with the image it is pulled through (stitchCrossings) its legs are in front of the
// head below by 2.3 r, as knitting has them. And the check does fail: the stitch mirrored through
// the head below has its legs behind it.
void expectSidewaysStitchHeld(int width, int a1, int a0, const char* name) {
    const Chart chart = zigzagChart(width, a1, a0, name);
    const ChartCell cell = chartToCell(chart);
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    ChartPattern cp;
    expectZigzagRelaxesHooked(chart, cell, name, &cp);
    ChartCell relaxed = cp.cell;
    relaxed.pattern = cp.relaxed.pattern;
    const int c = width - 1;
    const test::Frame f = test::stitchFrame(relaxed, 1, c);
    std::printf("%s: stitch (1, %d) faces (%.3f, %.3f, %.3f)\n", name, c, f.n.x, f.n.y, f.n.z);
    EXPECT_GT(std::abs(f.n.x), 0.9);  // turned sideways
    // Flipped: the loop mirrored along its normal through the head below where its legs cross it.
    const std::vector<test::Crossing> crossings = test::stitchCrossings(relaxed, 1, c, f);
    ASSERT_GE(crossings.size(), 2u);
    const double head = crossings.back().zb;
    std::printf("%s: legs %.2f r in front of the head below\n", name,
                (crossings.back().at.z - head) / relaxed.pattern.radius);
    const StitchLoop& l = relaxed.loop(1, c);
    ChartCell flipped = relaxed;
    for (uint32_t i = l.first; i < l.first + l.count; ++i) {
        glm::dvec3& q = flipped.pattern.points[i];
        q -= 2 * (glm::dot(q, f.n) - head) * f.n;
    }
    EXPECT_NE(test::checkStitchEnds(flipped, 1, c), "");
}

TEST(Intarsia, aStitchStandingSidewaysBesideTheBoundaryThatStaysKeepsItsCrossings) {
    expectSidewaysStitchHeld(22, 9, 4, "carry5on22.chart");
}

TEST(Intarsia, aBoundaryMovingTenColumnsRelaxesWithEveryStitchHeld) {
    expectSidewaysStitchHeld(24, 12, 2, "carry10on24.chart");
}

// A move of half the repeat's width could be carried either way round: where the rows would have to
// continue (a block one row tall otherwise) it is refused naming the boundary; between blocks two
// rows tall each block has its own yarns, as before.
TEST(Intarsia, aBoundaryMovingHalfTheRepeatEitherWayIsRefusedWhereItMustBeCarried) {
    const auto error = parseError;
    const std::string tie =
        error("k k k k k k\nk k k k k k\n\nB B B A A A\nA A A B B B\nA=#ffffff B=#000000\nintarsia\n");
    EXPECT_NE(
        tie.find("t.chart:4:1: intarsia: the colour boundary left of column 1 in row 1 moves 3 columns into row 2, "
                 "and on this 6-stitch repeat 3 columns to the right and to the left land on the same place"),
        std::string::npos)
        << tie;
    EXPECT_NE(tie.find("Move the boundary by fewer than 3 columns"), std::string::npos) << tie;
    EXPECT_EQ(error("k k k k k k\nk k k k k k\nk k k k k k\nk k k k k k\n\nB B B A A A\nB B B A A A\n"
                    "A A A B B B\nA A A B B B\nA=#ffffff B=#000000\nintarsia\n"),
              "");
    // Two shifts of the areas as near (a 12-stitch repeat of 3-stitch stripes moving 3): a tie too.
    EXPECT_NE(error("k k k k k k k k k k k k\nk k k k k k k k k k k k\n\nB B B A A A B B B A A A\n"
                    "A A A B B B A A A B B B\nA=#ffffff B=#000000\nintarsia\n")
                  .find("intarsia: the colour boundary"),
              std::string::npos);
}

// Stripes moving two columns every row come back to themselves a period over: the closing turn
// changes tile in x and y one at a time (each edge of a periodic cell moves one period at most).
TEST(Intarsia, steepStripesCloseAPeriodOverWithEdgesOfOnePeriod) {
    const ChartCell cell = chartToCell(parseChart("k k k k k k\nk k k k k k\nk k k k k k\nk k k k k k\n\n"
                                                  "A A A A B B\nA A B B B B\nB B B B A A\nB B A A A A\n"
                                                  "A=#ffffff B=#000000\nintarsia\n",
                                                  "steep_stripes.chart"));
    EXPECT_EQ(cell.yarns, 2);
    const Pattern& p = cell.pattern;
    for (const PeriodicEdge& e : p.edges) EXPECT_LE(std::abs(e.dx) + std::abs(e.dy), 1);
    for (const YarnPath& y : yarnPaths(p)) {
        ASSERT_FALSE(y.open);
        int dx = 0, dy = 0;
        for (const uint32_t v : y.vertices) {
            dx += p.edges[v].dx;
            dy += p.edges[v].dy;
        }
        EXPECT_EQ(std::abs(dx), 1);
        EXPECT_EQ(dy, 1);
    }
    const Interlock il = interlock(cell, p);
    ASSERT_EQ(il.linkedWith.size(), 8u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
}

// The four-row steep stripes: at every boundary that moves, the arriving yarn's carried turn comes
// from one side and the leaving yarn's goes off to the other, each two stitches long behind the
// stitches it passes (the first two the yarn knits in the row above, or the last two of the row
// below, knitted back over). Free, the carried yarn was drawn tight like a drawstring: relaxed,
// stitch (1, 2) came to lie folded over, its right foot left of its left one, and lost knitting's
// crossing with the head below (docs/charts.md, "Diagonals"). Each carried turn's crossover is
// held behind those stitches, as a knitter's carried yarn lies on them; the turns whose boundary
// stays are free. Built, every stitch has knitting's four crossings with the loop below and the
// held vertices lie behind every loop. Relaxed (BM_RelaxIntarsiaCarried/steep_stripes in
// bench/chart_bench.cpp, 20-40 s wall on the shared machine) every stitch keeps the crossing with
// the head below.
TEST(Intarsia, steepStripesHoldTheirCarriedYarnBehindTheStitchesItPasses) {
    const ChartCell cell = chartToCell(parseChart("k k k k k k\nk k k k k k\nk k k k k k\nk k k k k k\n\n"
                                                  "A A A A B B\nA A B B B B\nB B B B A A\nB B A A A A\n"
                                                  "A=#ffffff B=#000000\nintarsia\n",
                                                  "steep_stripes.chart"));
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    const HeldTurns held = heldTurns(cell);  // 8 turns, 2 at a boundary that stays
    EXPECT_EQ(held.carried, 6);
    EXPECT_EQ(held.carriedHeld, 6);
    EXPECT_EQ(held.keptHeld, 0);
    EXPECT_EQ(held.offTurns, 0u);
    double front = 1e300;  // the loops' rearmost point
    for (const StitchLoop& l : cell.loops)
        for (uint32_t i = l.first; i < l.first + l.count; ++i) front = std::min(front, cell.pattern.points[i].z);
    for (const uint32_t v : cell.anchors) EXPECT_LT(cell.pattern.points[v].z, front) << v;
}

// Diagonal stripes (each row the areas one column to the left): each stripe's yarn climbs the
// cell and comes back to itself one period up and one period to the left, a closed yarn whose
// edges sum to (-1, 1) periods; its turns hook as in vertical bands.
TEST(Intarsia, aDiagonalStripesYarnClosesAPeriodOver) {
    const ChartCell cell = chartToCell(parseChart("k k k k\nk k k k\nk k k k\nk k k k\n\nB A A B\nB B A A\n"
                                                  "A B B A\nA A B B\nA=#ffffff B=#000000\nintarsia\n",
                                                  "stripes.chart"));
    EXPECT_EQ(cell.yarns, 2);
    const Pattern& p = cell.pattern;
    for (const YarnPath& y : yarnPaths(p)) {
        ASSERT_FALSE(y.open);
        int dx = 0, dy = 0;
        for (const uint32_t v : y.vertices) {
            dx += p.edges[v].dx;
            dy += p.edges[v].dy;
        }
        EXPECT_EQ(dx, -1);
        EXPECT_EQ(dy, 1);
    }
    const Interlock il = interlock(cell, p);
    ASSERT_EQ(il.linkedWith.size(), 8u);
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    EXPECT_GT(minYarnDistance(p), 0.3);
}

// Stripes one stitch wide moving a column every row (`B A B A` / `A B A B`): after the chart's two
// rows each area arrives on the other area of its colour, so the cell stacks the rows to four, where
// each comes back to itself, one period over: four closed yarns (one per area of a row), each
// turn hooked through the neighbours' turns above and below, every stitch with knitting's
// crossings; the designer is told the repeat became four rows tall.
TEST(Intarsia, areasThatWanderOntoAnotherOfTheirColourAreStackedUntilEachComesBack) {
    const Chart chart = parseChart("k k k k\nk k k k\n\nB A B A\nA B A B\nA=#ffffff B=#000000\nintarsia\n", "t");
    const ChartCell cell = chartToCell(chart);
    EXPECT_EQ(cell.height, 4);
    EXPECT_EQ(cell.pattern.rowsPerPeriod, 4);
    EXPECT_EQ(cell.stacking.times, 2);
    EXPECT_TRUE(cell.stacking.wandering);
    EXPECT_NE(stackingWarning(chart, cell.stacking).find("the chart's repeat is knitted 4 rows tall"),
              std::string::npos);
    EXPECT_EQ(cell.yarns, 4);
    const Pattern& p = cell.pattern;
    const std::vector<YarnPath> paths = yarnPaths(p);
    ASSERT_EQ(paths.size(), 4u);
    for (const YarnPath& y : paths) {
        ASSERT_FALSE(y.open);
        int dx = 0, dy = 0;
        for (const uint32_t v : y.vertices) {
            dx += p.edges[v].dx;
            dy += p.edges[v].dy;
        }
        EXPECT_EQ(dx, 1);
        EXPECT_EQ(dy, 1);
    }
    for (const StitchLoop& l : cell.loops) {  // each row's loops on four yarns, one colour each
        EXPECT_EQ(cell.colour[size_t(l.row * cell.width + l.column)],
                  chart.palette.at(chart.colourAt(l.row % 2, l.column)));
    }
    const Interlock il = interlock(cell, p);
    ASSERT_EQ(il.linkedWith.size(), 16u);  // a turn per yarn and row
    for (const int n : il.linkedWith) EXPECT_EQ(n, 2);
    EXPECT_LT(il.worstUnlinked, kSurelyFree);
    for (int r = 0; r < cell.height; ++r)
        for (int c = 0; c < cell.width; ++c) EXPECT_EQ(test::checkStitch(cell, r, c), "") << r << ", " << c;
    EXPECT_GT(minYarnDistance(p), 0.3);
    // Bands and the diagonal stripes that come back to themselves are not stacked.
    EXPECT_FALSE(chartToCell(builtinChart("chart:intarsia-blocks")).stacking.wandering);
    EXPECT_EQ(chartStacking(builtinChart("chart:intarsia-blocks")).times, 1);
}

// Stripes one stitch wide round a 100-stitch period, each moving a column a row, come back to
// themselves after 100 rows: the stacked cell (10000 stitches) is refused before anything is
// built, with its size and why it is that tall.
TEST(Intarsia, aStackTooLargeToRelaxIsRefusedWithItsSize) {
    std::string stitches, even, odd;  // rows A B A B ... and B A B A ...
    for (int c = 0; c < 100; ++c) {
        const std::string gap = c ? " " : "";
        stitches += gap + "k";
        even += gap + (c % 2 ? "B" : "A");
        odd += gap + (c % 2 ? "A" : "B");
    }
    const Chart chart = parseChart(
        stitches + "\n" + stitches + "\n\n" + odd + "\n" + even + "\nA=#ffffff B=#000000\nintarsia\n", "wide.chart");
    EXPECT_EQ(chartStacking(chart).rows, 100);
    try {
        relaxChart(chart);
        FAIL() << "relaxed";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("wide.chart: intarsia: the colour areas move round the period"), std::string::npos) << what;
        EXPECT_NE(what.find("100 rows x 100 stitches at 24 samples per stitch make at least 240000 yarn vertices, "
                            "more than 48000"),
                  std::string::npos)
            << what;
    }
}

// Not run by default (--gtest_also_run_disabled_tests; 6.5 s): the evidence behind interlock's open
// arcs (docs/charts.md, "Issue 25 round 10: long carries"). Relaxes the 20-stitch zigzag whose
// boundary moves six columns, and at every iteration measures each pair of turns of the two yarns
// two ways: closed out in front of the work (rays from the feet one period out along +z, joined
// there; the count before round 10), split into the Gauss integral's four terms (turn-turn,
// turn-closure, closure-turn, closure-closure), printing every change of a rounded linking number
// with the terms before and after; and as open arcs (interlock), printing the smallest hooked and
// largest free mean linking number over the run.
TEST(Intarsia, DISABLED_closuresOfLongCarriesCrossWhileTheTurnsStayHooked) {
    const Chart chart = zigzagChart(20, 10, 4, "carry6on20.chart");
    const ChartCell cell = chartToCell(chart);
    struct Pair {
        size_t a, b;
        glm::dvec3 shift;  // in periods
    };
    std::vector<Pair> pairs;  // as interlock chooses them on the built cell
    {
        const std::vector<TurnCurve> t = turnsOf(cell, cell.pattern);
        const Pattern& p = cell.pattern;
        for (size_t a = 0; a < t.size(); ++a)
            for (size_t b = a + 1; b < t.size(); ++b) {
                if (t[a].yarn == t[b].yarn) continue;
                const glm::dvec3 d = t[a].centre - t[b].centre;
                for (int iy = -1; iy <= 1; ++iy)
                    pairs.push_back({a, b, {std::round(d.x / p.px), std::round(d.y / p.py) + iy, 0}});
            }
    }
    // The terms of the linking number of a and b (moved), each closed out in front.
    auto terms = [](const Pattern& p, const TurnCurve& a, const TurnCurve& b, glm::dvec3 shift) {
        auto closed = [&](const std::vector<glm::dvec3>& v, glm::dvec3 by) {
            std::vector<glm::dvec3> out;
            for (const glm::dvec3& q : v) out.push_back(q + by);
            const glm::dvec3 e = out.back(), f = out.front();
            out.push_back({e.x, e.y, e.z + p.px});
            out.push_back({f.x, f.y, f.z + p.px});
            return out;
        };
        const std::vector<glm::dvec3> A = closed(a.points, glm::dvec3(0.0)),
                                      B = closed(b.points, shift * glm::dvec3(p.px, p.py, 0));
        std::array<double, 4> out{0, 0, 0, 0};  // turn-turn, turn-closure, closure-turn, closure-closure
        for (size_t i = 0; i < A.size(); ++i)
            for (size_t j = 0; j < B.size(); ++j) {
                const bool ca = i + 3 >= A.size(), cb = j + 3 >= B.size();
                out[size_t(2 * ca + cb)] +=
                    linking({A[i], A[(i + 1) % A.size()]}, {B[j], B[(j + 1) % B.size()]}, false);
            }
        return out;
    };
    std::vector<std::array<double, 4>> last;
    double hooked = 1e300, free = 0;
    auto measure = [&](const Pattern& p, int iteration) {
        const std::vector<TurnCurve> t = turnsOf(cell, p);
        std::vector<std::array<double, 4>> now;
        for (const Pair& q : pairs) {
            now.push_back(terms(p, t[q.a], t[q.b], q.shift));
            std::vector<glm::dvec3> moved;
            for (const glm::dvec3& x : t[q.b].points) moved.push_back(x + q.shift * glm::dvec3(p.px, p.py, 0));
            const double open = std::abs(linking(t[q.a].points, moved, false));
            if (open > kHooked) hooked = std::min(hooked, open);
            else free = std::max(free, open);
        }
        for (size_t k = 0; k < now.size() && !last.empty(); ++k) {
            const auto sum = [](const std::array<double, 4>& x) { return x[0] + x[1] + x[2] + x[3]; };
            if (std::lround(sum(now[k])) == std::lround(sum(last[k]))) continue;
            std::printf("iteration %d, turns %zu and %zu (%+g, %+g periods): closed in front %+.3f -> %+.3f; "
                        "turn-turn %+.3f -> %+.3f, turn-closure %+.3f -> %+.3f, closure-turn %+.3f -> %+.3f, "
                        "closure-closure %+.3f -> %+.3f\n",
                        iteration, pairs[k].a, pairs[k].b, pairs[k].shift.x, pairs[k].shift.y, sum(last[k]),
                        sum(now[k]), last[k][0], now[k][0], last[k][1], now[k][1], last[k][2], now[k][2], last[k][3],
                        now[k][3]);
        }
        last = now;
    };
    measure(cell.pattern, 0);
    ChartPatternOptions options;
    options.stepInterval = 1;
    options.onStep = [&](const RelaxStep& step) {
        measure(step.pattern, step.iteration);
        return true;
    };
    const ChartPattern cp = relaxChart(chart, options);
    measure(cp.relaxed.pattern, cp.relaxed.iterations);
    std::printf("%d iterations, closest approach %.3f r; open turns: hooked pairs >= %.3f, free pairs <= %.3f\n",
                cp.relaxed.iterations, cp.relaxed.closestApproach, hooked, free);
}

}  // namespace
}  // namespace knit
