// From a stitch chart to an initial periodic yarn cell: one course per row, one loop per stitch,
// heights that give every crossing its over/under by construction (see knit/chart_topology.hpp).
#include "knit/chart_topology.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "chart_intarsia.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

// The plain-knit loop of generateStockinette, in model units (yarn radius kModelRadius).
constexpr double kLoopWidth = 1.5;   // a: sideways bulge of the legs
constexpr double kLoopHeight = 4.0;  // h
constexpr double kDepth = 1.0;       // d: height of heads, feet and legs above/below the mid-surface
constexpr double kRowPitch = 4.5;    // h + row gap
constexpr double kModelRadius = 0.8;
// Where, along a loop (t in [-pi, pi), head at t = 0), the crossings with the neighbouring
// rows lie: the head is crossed by the legs above around |t| ~ 0.36, the legs are crossed by
// the feet above around |t| ~ 1.45 and cross the head below around |t| ~ 1.7, the feet cross
// the legs below around |t| ~ 2.78. Changes of height happen between them.
constexpr double kLegSwitch0 = 1.47, kLegSwitch1 = 1.67;  // upper -> lower stitch kind
constexpr double kFootBlend = 0.36;                       // neighbouring columns' kinds meet at the foot
// A row below a cable row is stretched: the upper part of its loops (head and upper legs, all
// that the row above touches) rises by kCableLift and, for the cable's loops, moves to the new
// column, between the crossing with the feet above (|t| ~ 1.45) and the crossing with the head
// below (|t| ~ 1.7). The cable's legs cross there, kCableDepth apart in height.
constexpr double kShift0 = 1.5, kShift1 = 1.66;
constexpr double kCableLift = 3.0;
constexpr double kCableDepth = 1.0;
// Such loops are sampled densely around |t| = pi / 2 (t = u + kWarp sin 2u, monotone for
// kWarp < 1/2), so the long cable legs get several vertices.
constexpr double kWarp = 0.4;

// Round 2 constructs (model units).
constexpr double kStackDepth = 0.6;           // z between the upper parts of loops one stitch takes together
constexpr double kStackShift = 0.35;          // x between their heads, so their legs cross in projection
constexpr double kFloatDepth = 2.4;           // |z| of a float (behind or in front of the stitches it passes)
constexpr double kStrandStep = 0.9;           // further depth of each further stranded float in a column
constexpr double kFloatDrop = 2.5;            // a float runs this far below its row's loop centres
constexpr double kFloatEnd = 1.2;             // parameter span over which a float meets a foot
constexpr double kStrandedFloatSlack = 0.95;  // rest-length factor of stranded floats (docs/charts.md)
constexpr double kTuckDepth = 1.6;            // z of a tuck loop's lower part (behind the held loop)
constexpr double kTuckFoot = 0.6;             // parameter span over which it meets its feet
// Where a stranded yarn's loop meets its float beside another yarn's loop, both feet step back
// from the shared foot point (inwards and up or down), so the two yarns do not meet there.
constexpr double kJunctionX = 0.5, kJunctionY = 0.6, kJunctionSpan = 0.8;
constexpr double kThirdRowYarn = 0.25;          // extra yarn (in plain loops) of a loop held a third row
constexpr double kTwist0 = 1.3, kTwist1 = 1.9;  // a twisted loop's halves swap sides between these |t|
constexpr double kTwistDepth = 0.7, kTwistWidth = 0.15;

double sign(StitchKind k) { return k == StitchKind::Knit ? 1.0 : -1.0; }
double smooth(double a, double b, double x) {  // 0 at a, 1 at b (either order)
    const double u = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return u * u * (3 - 2 * u);
}
int wrap(int i, int n) { return ((i % n) + n) % n; }
bool held(StitchOp op) { return op == StitchOp::Slip || op == StitchOp::SlipFront || op == StitchOp::Tuck; }
bool makesLoop(StitchOp op) { return op != StitchOp::Slip && op != StitchOp::SlipFront; }

// Step 1: the yarns of each row. One per row, or for stranded colourwork one per colour the row
// uses (in order of first use), for intarsia one per colour area of the row;
// yarnOf[c] is the row's yarn that works column c.
struct RowYarns {
    std::vector<char> colours;
    std::vector<int> yarnOf;
};
std::vector<RowYarns> rowYarns(const Chart& chart) {
    std::vector<RowYarns> rows(size_t(chart.height));
    if (chart.colourwork == Colourwork::Intarsia) {
        for (int r = 0; r < chart.height; ++r) {
            RowYarns& y = rows[size_t(r)];
            y.yarnOf.assign(size_t(chart.width), 0);
            for (const intarsia::Area& a : intarsia::areas(chart, r)) {
                for (int k = 0; k < a.count; ++k) y.yarnOf[size_t((a.first + k) % chart.width)] = int(y.colours.size());
                y.colours.push_back(a.colour);
            }
        }
        return rows;
    }
    const bool stranded = chart.colourwork == Colourwork::Stranded;
    for (int r = 0; r < chart.height; ++r) {
        RowYarns& y = rows[size_t(r)];
        for (int c = 0; c < chart.width; ++c) {
            const char colour = chart.colour.empty() ? char(0) : chart.colourAt(r, c);
            const char key = stranded ? colour : char(0);
            const auto it = std::find(y.colours.begin(), y.colours.end(), key);
            y.yarnOf.push_back(int(it - y.colours.begin()));
            if (it == y.colours.end()) y.colours.push_back(key);
        }
    }
    return rows;
}

// Step 2: what the rows above do to each loop (row, column) a course makes: the stitch pulled
// through it (column, kind, a cable's cross), the rows it is held for, its place in the stack of
// loops that stitch takes together; and for every stitch the loops it is pulled through.
struct Plan {
    int consumerColumn = 0;
    double up = 1;  // sign of the stitch pulled through it
    bool cable = false, front = true;
    int lift = 0, stackIndex = 0, stackSize = 1, stackRank = 0;  // rank: left to right among the stack
    std::vector<LoopRef> through;
};
std::vector<Plan> planLoops(const Chart& chart) {
    const int W = chart.width, H = chart.height;
    std::vector<Plan> plan(size_t(W) * size_t(H));
    for (int c = 0; c < W; ++c)
        for (int r = 0; r < H; ++r) plan[size_t(r) * size_t(W) + size_t(c)].consumerColumn = c;
    for (int R = 0; R < H; ++R)
        for (int C = 0; C < W; ++C) {
            const StitchOp op = chart.opAt(R, C);
            if (held(op)) continue;
            // The loops taken: for each source, the loop at the bottom of its chain of slipped or
            // tucked cells, then the tuck loops laid behind it (lowest first).
            std::vector<std::pair<LoopRef, int>> taken;  // (loop, unwrapped row)
            for (const int j : chart.sources(R, C)) {
                int rr = R - 1, cc = j;
                std::vector<std::pair<LoopRef, int>> tucks;
                for (int guard = 0; held(chart.opAt(wrap(rr, H), cc)) && guard <= H; ++guard) {
                    if (chart.opAt(wrap(rr, H), cc) == StitchOp::Tuck) tucks.push_back({{wrap(rr, H), cc}, rr});
                    cc = chart.sourceColumn(wrap(rr, H), cc);
                    --rr;
                }
                taken.push_back({{wrap(rr, H), cc}, rr});
                for (auto t = tucks.rbegin(); t != tucks.rend(); ++t) taken.push_back(*t);
            }
            std::vector<int> byColumn(taken.size());
            for (size_t k = 0; k < taken.size(); ++k) byColumn[k] = int(k);
            std::stable_sort(byColumn.begin(), byColumn.end(), [&](int a, int b) {
                return taken[size_t(a)].first.column < taken[size_t(b)].first.column;
            });
            const ChartCable* cable = nullptr;
            for (const ChartCable& cb : chart.cables)
                if (cb.row == R && C >= cb.column && C < cb.column + cb.left + cb.right) cable = &cb;
            Plan& stitch = plan[size_t(R) * size_t(W) + size_t(C)];
            for (size_t k = 0; k < taken.size(); ++k) {
                Plan& l = plan[size_t(taken[k].first.row) * size_t(W) + size_t(taken[k].first.column)];
                l.consumerColumn = C;
                l.up = sign(chart.at(R, C));
                l.cable = cable != nullptr;
                l.front = cable ? cable->front : true;
                l.lift = R - 1 - taken[k].second;
                l.stackIndex = int(k);
                l.stackSize = int(taken.size());
                l.stackRank = int(std::find(byColumn.begin(), byColumn.end(), int(k)) - byColumn.begin());
                stitch.through.push_back(taken[k].first);
            }
        }
    return plan;
}

// Step 3: where each row sits (rows whose loops' heads move sideways are stretched by kCableLift).
struct RowLayout {
    std::vector<double> y;        // y of each row's loop centres
    std::vector<bool> stretched;  // heads of this row move to other columns
    double period = 0;
    // The height the upper part of a loop of `row` rises to when its head sits `lift` rows up.
    double headRise(int row, int lift) const {
        const int n = int(y.size()), top = row + lift;
        const double yTop = y[size_t(wrap(top, n))] + period * double((top - wrap(top, n)) / n);
        return yTop - y[size_t(row)] + (stretched[size_t(wrap(top, n))] ? kCableLift : 0.0);
    }
};
RowLayout rowLayout(const Chart& chart, const std::vector<Plan>& plan) {
    RowLayout rows;
    for (int r = 0; r < chart.height; ++r) {
        bool moves = false;
        for (int c = 0; c < chart.width; ++c)
            moves = moves || (makesLoop(chart.opAt(r, c)) &&
                              plan[size_t(r) * size_t(chart.width) + size_t(c)].consumerColumn != c);
        rows.y.push_back(rows.period);
        rows.stretched.push_back(moves);
        rows.period += kRowPitch + (moves ? kCableLift : 0.0);
    }
    return rows;
}

// Everything a course's vertex needs about the cell it passes.
struct CellGeometry {
    const Chart* chart = nullptr;
    const RowLayout* rows = nullptr;
    const std::vector<Plan>* plan = nullptr;
    const RowYarns* yarns = nullptr;
    int yarn = 0;  // the row's yarn (index into yarns->colours)
    // How far a foot beside another yarn's loop steps back from the shared foot point.
    double junctionX = kJunctionX, junctionY = kJunctionY;
    const Plan& at(int r, int c) const { return (*plan)[size_t(r) * size_t(chart->width) + size_t(c)]; }
    bool loopOf(int r, int c) const {  // does this yarn make a loop at column c of row r?
        return yarns->yarnOf[size_t(c)] == yarn && makesLoop(chart->opAt(r, c));
    }
};

// Does another yarn make the loop at column c of row r (a colour change for this yarn)?
bool otherYarnsLoop(const CellGeometry& g, int r, int c) {
    return g.yarns->yarnOf[size_t(c)] != g.yarn && makesLoop(g.chart->opAt(r, c));
}

// How far (0..1) a loop's foot at t steps back from the foot point: towards 1 at the feet beside
// another yarn's loop.
double junctionOf(const CellGeometry& g, const StitchLoop& l, double t) {
    const int side = t < 0 ? -1 : 1;
    if (!otherYarnsLoop(g, l.row, wrap(l.column + side, g.chart->width))) return 0.0;
    return smooth(util::kPi - kJunctionSpan, util::kPi, std::abs(t));
}

// The z sign of a loop's foot side: the neighbouring loop's kind when this yarn makes it, else its own.
double neighbourSign(const CellGeometry& g, const StitchLoop& l, int side) {
    const int c = wrap(l.column + side, g.chart->width);
    return g.loopOf(l.row, c) ? sign(g.chart->at(l.row, c)) : sign(l.kind);
}

// Step 4a: one vertex of a loop at parameter t, in model units.
glm::dvec3 loopPoint(const CellGeometry& g, const StitchLoop& l, double t) {
    const RowLayout& rows = *g.rows;
    const Plan& p = g.at(l.row, l.column);
    const double at = std::abs(t);
    const bool moves = rows.stretched[size_t(l.row)] || l.lift > 0 || l.stackSize > 1;
    // Plane: the plain-knit curve (a twisted loop's upper part traversed the other way); the
    // upper part lifted and moved to the stitch pulled through it.
    const double upper = moves ? smooth(kShift1, kShift0, at) : 0.0;
    const double half = (l.stackSize - 1) / 2.0;
    const double twist = l.op == StitchOp::ThroughBack ? 2 * smooth(kTwist0, kTwist1, at) - 1 : 1.0;
    const double x = util::kTwoPi * (l.column + l.headShift * upper) + (half - p.stackRank) * kStackShift * upper +
                     twist * (t + kLoopWidth * std::sin(2 * t)) - (t < 0 ? -1 : 1) * g.junctionX * junctionOf(g, l, t);
    double y = rows.y[size_t(l.row)] + kLoopHeight * std::cos(t) + upper * rows.headRise(l.row, l.lift);
    y += (t < 0 ? -1 : 1) * g.junctionY * junctionOf(g, l, t);
    // Height: the upper half follows the stitch pulled through this loop, the lower half this
    // stitch; at the feet the neighbouring column's kind takes over half-way.
    const double neighbour = neighbourSign(g, l, t < 0 ? -1 : 1);
    const double s = sign(l.kind);
    const double low = s + 0.5 * (neighbour - s) * smooth(util::kPi - kFootBlend, util::kPi, at);
    double z = -kDepth * std::cos(2 * t) * (p.up + (low - p.up) * smooth(kLegSwitch0, kLegSwitch1, at));
    if (l.op == StitchOp::Tuck) {  // the lower part behind the held loop, meeting its feet
        const double zUp = -kDepth * std::cos(2 * t) * p.up;
        const double zLow =
            -kTuckDepth + (-kDepth * 0.5 * (s + neighbour) + kTuckDepth) * smooth(util::kPi - kTuckFoot, util::kPi, at);
        z = zUp + (zLow - zUp) * smooth(kLegSwitch0, kLegSwitch1, at);
    }
    // Cable legs, where they cross: the left-moving ones in front for a front cross.
    if (l.headShift != 0 && p.cable) {
        const double bump = std::sin(util::kPi * upper);
        z += ((l.headShift < 0) == p.front ? 1.0 : -1.0) * kCableDepth * kDepth * bump;
    }
    // Loops taken together: the top one in front.
    z += (half - l.stackIndex) * kStackDepth * std::min(1.0, 2 * upper);
    // A twisted loop's halves cross at its base, the strand from the left foot in front.
    if (l.op == StitchOp::ThroughBack) {
        const double u = (at - 0.5 * (kTwist0 + kTwist1)) / kTwistWidth;
        z += (t < 0 ? 1.0 : -1.0) * kTwistDepth * std::exp(-u * u);
    }
    return {x, y, z};
}

// The depth of yarn `yarn`'s float at column c of row r (it does not make the loop there).
double floatDepth(const CellGeometry& g, int r, int c) {
    const int worker = g.yarns->yarnOf[size_t(c)];
    if (worker == g.yarn) return g.chart->opAt(r, c) == StitchOp::SlipFront ? kFloatDepth : -kFloatDepth;
    const int rank = g.yarn < worker ? g.yarn : g.yarn - 1;  // among the yarns floating here
    return -(kFloatDepth + kStrandStep * rank);
}

// Step 4b: one vertex of a float at column c (t as for a loop): at the height of the course's
// lower half, meeting the neighbouring loop's foot or the neighbouring float.
glm::dvec3 floatPoint(const CellGeometry& g, int r, int c, double t) {
    const double yMid = g.rows->y[size_t(r)] - kFloatDrop, zMid = floatDepth(g, r, c);
    const int side = t < 0 ? -1 : 1, n = wrap(c + side, g.chart->width);
    double xEnd = 0, yEnd = yMid, zEnd = 0.5 * (zMid + floatDepth(g, r, n));
    if (g.loopOf(r, n)) {  // its foot on side -side, stepped back when this column is another yarn's loop
        const double j = otherYarnsLoop(g, r, c) ? 1.0 : 0.0;
        xEnd = side * kJunctionX * j;
        yEnd = g.rows->y[size_t(r)] - kLoopHeight - side * kJunctionY * j;
        zEnd = -kDepth * sign(g.chart->at(r, n));
    }
    const double e = smooth(util::kPi - kFloatEnd, util::kPi, std::abs(t));
    return {util::kTwoPi * c + t + xEnd * e, yMid + (yEnd - yMid) * e, zMid + (zEnd - zMid) * e};
}

// Vertices of a float column: its yarn is about a third as long as a loop's, so about a third of
// the loop's samples keep the segments as long as the loops' (the contact skips only the two
// neighbouring segments along a yarn, so shorter ones would push a float's own vertices apart).
int floatSamples(int n) { return std::max(3, (n + 1) / 3); }

// The first vertex of each column of one yarn of row r (and one past its last), from `first`.
std::vector<uint32_t> columnStarts(const CellGeometry& g, int r, int n, uint32_t first) {
    std::vector<uint32_t> starts{first};
    for (int c = 0; c < g.chart->width; ++c)
        starts.push_back(starts.back() + uint32_t(g.loopOf(r, c) ? n : floatSamples(n)));
    return starts;
}

// The loop parameter of sample i of n: uniform, or dense around |t| = pi / 2 where the upper part
// moves (stretched rows, lifted loops). A cable's legs cross there, within |t| in [kShift0,
// kShift1], narrower than the samples' spacing: so on a cable's crossing loops u = +-pi / 2
// (t = +-pi / 2, inside it) is always a sample. Each quarter of u is then sampled uniformly,
// n / 4 samples each when 4 divides n (as plain uniform samples); else the quarters differ by
// one. Uniform samples missed it at 10 per stitch: both samples beside the crossing got no cable
// depth and the legs were built 0.011 r apart (ChartTopology.cableLegsAreBuiltApartAtAnySampling).
double loopParameter(const CellGeometry& g, const StitchLoop& l, int i, int n) {
    double u = -util::kPi + util::kTwoPi * i / n;
    if (!g.rows->stretched[size_t(l.row)] && l.lift == 0) return u;
    if (l.headShift != 0 && g.at(l.row, l.column).cable && n % 4 != 0) {  // its legs cross (loopPoint)
        const int quarter[5] = {0, n / 4, n / 2, n - n / 4, n};           // the samples at u = -pi, -pi/2, 0, pi/2, pi
        int q = 0;
        while (i >= quarter[q + 1]) ++q;
        u = -util::kPi + util::kPi / 2 * (q + double(i - quarter[q]) / (quarter[q + 1] - quarter[q]));
    }
    return u + kWarp * std::sin(2 * u);
}

// The floats of one yarn of a row: its runs of columns without a loop (cyclic).
void addFloats(const CellGeometry& g, int r, int globalYarn, const std::vector<uint32_t>& columnFirst,
               std::vector<ChartFloat>& out) {
    const int W = g.chart->width;
    int start = 0;
    while (start < W && !g.loopOf(r, start)) ++start;
    const bool all = start == W;
    if (all) start = 0;
    for (int k = 0; k < W;) {
        const int c = (start + k) % W;
        if (g.loopOf(r, c)) {
            ++k;
            continue;
        }
        ChartFloat f;
        f.row = r;
        f.firstColumn = c;
        f.yarn = globalYarn;
        f.colour = g.yarns->colours[size_t(g.yarn)];
        f.front = true;
        for (; k < W && !g.loopOf(r, (start + k) % W); ++k) {
            const int cc = (start + k) % W;
            f.front = f.front && g.yarns->yarnOf[size_t(cc)] == g.yarn && g.chart->opAt(r, cc) == StitchOp::SlipFront;
            f.stranded = f.stranded || g.yarns->yarnOf[size_t(cc)] != g.yarn;
            for (uint32_t i = columnFirst[size_t(cc)]; i < columnFirst[size_t(cc) + 1]; ++i) f.vertices.push_back(i);
            ++f.columns;
        }
        if (f.colour == 0 && !g.chart->colour.empty()) f.colour = g.chart->colourAt(r, c);
        out.push_back(f);
    }
}

// Step 8: lifted loops hold a plain loop's yarn: their edges' rest lengths are scaled by the
// plain loop's length over theirs.
std::vector<double> liftedRestScale(const ChartCell& cell, double metresPerUnit, int n) {
    const Pattern& p = cell.pattern;
    std::vector<double> scale(p.points.size(), 1.0);
    double plain = 0;
    for (int i = 0; i < n; ++i) {
        auto at = [&](int k) {
            const double t = -util::kPi + util::kTwoPi * k / n;
            return glm::dvec3(t + kLoopWidth * std::sin(2 * t), kLoopHeight * std::cos(t), -kDepth * std::cos(2 * t));
        };
        plain += glm::length(at(i + 1) - at(i)) * metresPerUnit;
    }
    for (const StitchLoop& l : cell.loops) {
        if (l.lift == 0 || !l.madeLoop) continue;
        double length = 0;
        for (uint32_t i = l.first; i < l.first + l.count; ++i) {
            const PeriodicEdge& e = p.edges[i];
            length += glm::length(p.points[e.v1] + glm::dvec3(e.dx * p.px, e.dy * p.py, 0) - p.points[e.v0]);
        }
        // A loop held on a third row draws a quarter of a plain loop's yarn from its neighbours
        // (with a plain loop's length it pulled three rows so tight that the yarns came to
        // 1.868 r apart; with this, 1.964 r: docs/charts.md).
        const double held = plain * (1 + kThirdRowYarn * std::max(0, l.lift - 2));
        for (uint32_t i = l.first; i < l.first + l.count; ++i) scale[i] = std::min(1.0, held / length);
    }
    // Stranded floats hold a little less yarn than the loose construction gives them (0.95 of
    // it, on top of the relaxation's rest length): with the construction's length the relaxed
    // band's stitches stood 0.17 r further out than the same chart in one yarn, with 0.9-0.95 of
    // it 0.3 r less far (docs/charts.md, "Stranded floats").
    for (const ChartFloat& f : cell.floats)
        if (f.stranded)
            for (uint32_t v : f.vertices) scale[v] = kStrandedFloatSlack;
    return scale;
}

// Everything the cell is built from.
struct CellInputs {
    const Chart& chart;
    const std::vector<RowYarns>& yarns;
    const std::vector<Plan>& plan;
    const RowLayout& rows;
    int n = 0;  // samples per loop
};

// The record of the cell (r, c) on yarn `yarn`: its vertices [first, first + count).
StitchLoop stitchLoop(const CellInputs& in, int r, int c, int yarn, uint32_t first, uint32_t count) {
    const Plan& p = in.plan[size_t(r) * size_t(in.chart.width) + size_t(c)];
    StitchLoop l;
    l.row = r;
    l.column = c;
    l.yarn = yarn;
    l.first = first;
    l.count = count;
    l.kind = in.chart.at(r, c);
    l.op = in.chart.opAt(r, c);
    l.madeLoop = makesLoop(l.op);
    l.sourceColumn = in.chart.sourceColumn(r, c);
    l.headShift = p.consumerColumn - c;
    l.lift = p.lift;
    l.stackIndex = p.stackIndex;
    l.stackSize = p.stackSize;
    l.through = p.through;
    return l;
}

// Refuses a chart that would make more than kMaxChartVertices vertices (before allocating them).
void checkVertexCount(const Chart& chart, uint64_t count) {
    if (count > kMaxChartVertices)
        throw Error(chart.name + ": the chart makes more than " + std::to_string(kMaxChartVertices) +
                    " yarn vertices (" + std::to_string(chart.width) + " x " + std::to_string(chart.height) +
                    " stitches): a chart is one period of the fabric");
}

// Step 5: each yarn's columns (a loop: n vertices, a float: fewer), rows in order, and the
// stitch record: which yarn's vertices make each cell. Returns the columns' first vertices.
std::vector<std::vector<uint32_t>> stitchRecord(const CellInputs& in, ChartCell& cell) {
    const Chart& chart = in.chart;
    std::vector<std::vector<uint32_t>> starts;  // per yarn
    uint64_t next = 0;
    for (int r = 0; r < chart.height; ++r) {
        const RowYarns& ry = in.yarns[size_t(r)];
        const int firstYarn = int(starts.size());
        for (size_t k = 0; k < ry.colours.size(); ++k) {
            const CellGeometry g{&chart, &in.rows, &in.plan, &ry, int(k)};
            // The vertex count, bounded before anything is allocated for it.
            uint64_t count = 0;
            for (int c = 0; c < chart.width; ++c) count += uint64_t(g.loopOf(r, c) ? in.n : floatSamples(in.n));
            checkVertexCount(chart, next + count);
            starts.push_back(columnStarts(g, r, in.n, uint32_t(next)));
            next = starts.back().back();
        }
        for (int c = 0; c < chart.width; ++c) {
            const int yarn = firstYarn + ry.yarnOf[size_t(c)];
            const uint32_t first = starts[size_t(yarn)][size_t(c)];
            cell.loops.push_back(stitchLoop(in, r, c, yarn, first, starts[size_t(yarn)][size_t(c) + 1] - first));
        }
    }
    cell.yarns = int(starts.size());
    return starts;
}

// Step 6a: the vertices of row r's yarn k (global index `yarn`) whose columns start at `at` (model
// units times `scale`), closing through +x, with its floats; `letter` gets each vertex's
// palette letter. cell.loops holds the row's stitch record.
void addCourse(const CellInputs& in, int r, int k, int yarn, const std::vector<uint32_t>& at, double scale,
               ChartCell& cell, std::vector<char>& letter) {
    const Chart& chart = in.chart;
    const RowYarns& ry = in.yarns[size_t(r)];
    Pattern& p = cell.pattern;
    const CellGeometry g{&chart, &in.rows, &in.plan, &ry, k};
    for (int c = 0; c < chart.width; ++c) {
        const StitchLoop& l = cell.loop(r, c);
        const bool mine = g.loopOf(r, c);
        const int m = int(at[size_t(c) + 1] - at[size_t(c)]);
        for (int i = 0; i < m; ++i) {
            const double t = mine ? loopParameter(g, l, i, m) : -util::kPi + util::kTwoPi * i / m;
            p.points.push_back((mine ? loopPoint(g, l, t) : floatPoint(g, r, c, t)) * scale);
            letter.push_back(chart.colour.empty()                       ? char(0)
                             : chart.colourwork == Colourwork::Stranded ? ry.colours[size_t(k)]
                                                                        : chart.colourAt(r, c));
        }
    }
    const uint32_t first = at.front(), last = at.back() - 1;
    for (uint32_t i = first; i < last; ++i) p.edges.push_back({i, i + 1, 0, 0});
    p.edges.push_back({last, first, 1, 0});
    addFloats(g, r, yarn, at, cell.floats);
}

// Step 6: the vertices (model units times `scale`), yarn by yarn along each row; every yarn
// closes through +x. Returns the palette letter of every vertex.
std::vector<char> buildYarns(const CellInputs& in, const std::vector<std::vector<uint32_t>>& starts, double scale,
                             ChartCell& cell) {
    const Chart& chart = in.chart;
    Pattern& p = cell.pattern;
    std::vector<char> letter;
    const size_t vertices = starts.empty() ? 0 : starts.back().back();
    p.points.reserve(vertices);
    p.edges.reserve(vertices);
    letter.reserve(vertices);
    int yarn = 0;
    for (int r = 0; r < chart.height; ++r)
        for (size_t k = 0; k < in.yarns[size_t(r)].colours.size(); ++k, ++yarn)
            addCourse(in, r, int(k), yarn, starts[size_t(yarn)], scale, cell, letter);
    return letter;
}

// The length (model units) of a plain loop sampled with n vertices.
double plainLoopLength(int n) {
    double length = 0;
    for (int i = 0; i < n; ++i) {
        auto at = [&](int k) {
            const double t = -util::kPi + util::kTwoPi * k / n;
            return glm::dvec3(t + kLoopWidth * std::sin(2 * t), kLoopHeight * std::cos(t), -kDepth * std::cos(2 * t));
        };
        length += glm::length(at(i + 1) - at(i));
    }
    return length;
}

// One intarsia yarn being built: its vertices' tiles (a column of an area that wraps round the
// period is built where it is, one period back in x; a row of a block that runs past the chart's
// last row one period up in y) and its floats.
struct IntarsiaYarn {
    std::vector<int> tileX, tileY;
    std::vector<ChartFloat> floats;
    // The vertices held where they are built (ChartCell::anchors): its tails, and the crossover of
    // each turn carried two stitches on, which lies on the back of the stitches it passes.
    std::vector<uint32_t> anchored;
};

// A row of an area's serpentine: the area's place in the row (its first column unwrapped along the
// block) and its colour, the global yarn, the unwrapped row, the direction, and what follows the
// row (a turn up into the next row, where the yarn's first column is `nextColumn`, unwrapped, and
// its area's index among that row's areas `nextIndex`; or the block ends with a tail); and whether
// a tail comes before it (the block's first row).
struct SerpentineRow {
    intarsia::Place place;
    char colour = 0;
    int yarn = 0, row = 0, nextColumn = 0, nextIndex = 0;
    bool rightwards = true, turns = true, startTail = false, endTail = false;
};

// An unwrapped column's tile (whole periods in x, floor) and its column in the chart.
int tileOf(int u, int width) { return u >= 0 ? u / width : -((width - 1 - u) / width); }

// One row of an intarsia area's yarn, in its direction: (the starting tail,) loops (or a float
// past a slipped stitch), then the turn at the boundary up into the next row or the end tail.
void intarsiaRow(const CellInputs& in, const SerpentineRow& sr, double scale, ChartCell& cell, IntarsiaYarn& yarn,
                 std::vector<char>& letter) {
    const Chart& chart = in.chart;
    const intarsia::Place& area = sr.place;
    const int W = chart.width, H = chart.height, n = in.n, r = sr.row % H, oy = sr.row / H;
    const double spacing = plainLoopLength(n) / n;
    Pattern& p = cell.pattern;
    auto add = [&](const glm::dvec3& q, int ox) {
        p.points.push_back(q * scale);
        yarn.tileX.push_back(ox);
        yarn.tileY.push_back(oy);
        letter.push_back(sr.colour);
    };
    const CellGeometry g{&chart, &in.rows, &in.plan, &in.yarns[size_t(r)], area.index, intarsia::kBoundaryInset, 0.0};
    const double dir = sr.rightwards ? 1.0 : -1.0;
    // A tail lies behind two stitches of its row, or one when the second is not a loop of this
    // yarn (a slipped stitch's float lies where the tail would).
    auto tailStitches = [&](int fromU, int inward) {
        return area.count >= 2 && g.loopOf(r, wrap(fromU + inward, W)) ? 2 : 1;
    };
    const int firstU = sr.rightwards ? area.first : area.first + area.count - 1;
    if (sr.startTail) {  // behind the row's first stitches, ending at its first foot
        const glm::dvec3 foot = loopPoint(g, stitchLoop(in, r, wrap(firstU, W), sr.yarn, 0, 0), -dir * util::kPi);
        std::vector<glm::dvec3> tail = intarsia::tailPoints(foot, in.rows.y[size_t(r)], int(dir),
                                                            tailStitches(firstU, int(dir)), area.count == 1, spacing);
        for (auto q = tail.rbegin(); q != tail.rend(); ++q) {
            yarn.anchored.push_back(uint32_t(p.points.size()));
            add(*q, tileOf(firstU, W));
        }
    }
    bool floating = false;
    for (int k = 0; k < area.count; ++k) {
        const int u = area.first + (sr.rightwards ? k : area.count - 1 - k);  // unwrapped column
        const int c = wrap(u, W), ox = tileOf(u, W);
        const bool loop = g.loopOf(r, c);
        const int m = loop ? n : floatSamples(n);
        StitchLoop& l = cell.loops[size_t(r) * size_t(W) + size_t(c)];
        l = stitchLoop(in, r, c, sr.yarn, uint32_t(p.points.size()), uint32_t(m));
        l.reversed = !sr.rightwards;
        if (!loop) {  // a slipped stitch inside the area: the yarn floats past it
            if (!floating) yarn.floats.push_back({r, c, 0, sr.yarn, sr.colour, true, false, false, {}});
            ChartFloat& f = yarn.floats.back();
            f.firstColumn = sr.rightwards ? f.firstColumn : c;
            f.columns += 1;
            f.front = f.front && l.op == StitchOp::SlipFront;
            for (uint32_t i = 0; i < uint32_t(m); ++i) f.vertices.push_back(l.first + i);
        }
        floating = !loop;
        for (int i = 0; i < m; ++i) {
            const double t = dir * (loop ? loopParameter(g, l, i, m) : -util::kPi + util::kTwoPi * i / m);
            add(loop ? loopPoint(g, l, t) : floatPoint(g, r, c, t), ox);
        }
    }
    const int u = sr.rightwards ? area.first + area.count - 1 : area.first;
    const int c = wrap(u, W);
    const glm::dvec3 lastFoot = loopPoint(g, cell.loops[size_t(r) * size_t(W) + size_t(c)], dir * util::kPi);
    if (sr.endTail) {  // from the row's last foot back behind its last stitches
        add(lastFoot, tileOf(u, W));
        for (const glm::dvec3& q : intarsia::tailPoints(lastFoot, in.rows.y[size_t(r)], -int(dir),
                                                        tailStitches(u, -int(dir)), area.count == 1, spacing)) {
            yarn.anchored.push_back(uint32_t(p.points.size()));
            add(q, tileOf(u, W));
        }
    }
    if (!sr.turns) return;
    // The turn: from this row's last foot to the next row's first (the next period's row 0 after
    // the last row), at the boundary beside the row's last column and, a column over where the
    // boundary steps, beside the next row's first; built in this column's tile.
    const int next = (r + 1) % H, step = sr.nextColumn - u;
    const CellGeometry gn{&chart, &in.rows, &in.plan, &in.yarns[size_t(next)], sr.nextIndex, intarsia::kBoundaryInset,
                          0.0};
    intarsia::Turn turn;
    turn.from = lastFoot;
    turn.to = loopPoint(gn, stitchLoop(in, next, wrap(sr.nextColumn, W), sr.yarn, 0, 0), dir * util::kPi) +
              glm::dvec3(util::kTwoPi * (c + step - wrap(sr.nextColumn, W)), r + 1 == H ? in.rows.period : 0.0, 0);
    turn.boundary = util::kTwoPi * c + dir * util::kPi;
    turn.boundaryAbove = turn.boundary + util::kTwoPi * step;
    turn.side = sr.rightwards ? -1 : 1;
    // A turn into the next period's first row that also moves to another tile in x (the area
    // crossed the period's edge) changes tile one axis at a time: from its middle on it is built in
    // the next row's x tile, moved back by the periods between, and the edge into that row adds dy.
    const intarsia::TurnPoints tp = intarsia::turnPoints(turn, spacing);
    const std::vector<glm::dvec3>& points = tp.points;
    const int ox = tileOf(u, W), nx = r + 1 == H ? tileOf(sr.nextColumn, W) : ox;
    if (step != 0) {  // the carried yarn passes |step| stitches behind the work: a float in the row above
        const int edge = sr.rightwards ? u + 1 : u;  // the last foot's column edge
        yarn.floats.push_back(
            {next, wrap(std::min(edge, edge + step), W), std::abs(step), sr.yarn, sr.colour, false, false, true, {}});
    }
    for (size_t i = 0; i < points.size(); ++i) {
        const bool over = 2 * i >= points.size();
        if (tp.crossover[i]) yarn.floats.back().vertices.push_back(uint32_t(p.points.size()));
        if (tp.held[i]) yarn.anchored.push_back(uint32_t(p.points.size()));
        add(points[i] - glm::dvec3(over ? util::kTwoPi * W * (nx - ox) : 0.0, 0, 0), over ? nx : ox);
    }
}

// The edges of an intarsia yarn built from vertex `first` on: along it, and (closed) from its
// last vertex back to its first one period up and `shift` periods over (its area moved round the
// period in x on the way up: a diagonal stripe).
void intarsiaEdges(const IntarsiaYarn& yarn, uint32_t first, bool closed, int shift, Pattern& p) {
    const uint32_t last = uint32_t(p.points.size()) - 1;
    for (uint32_t i = first; i < last; ++i)
        p.edges.push_back({i, i + 1, yarn.tileX[i + 1 - first] - yarn.tileX[i - first],
                           yarn.tileY[i + 1 - first] - yarn.tileY[i - first]});
    if (closed)
        p.edges.push_back(
            {last, first, shift + yarn.tileX.front() - yarn.tileX.back(), 1 + yarn.tileY.front() - yarn.tileY.back()});
}

// A block of one colour: each row a plain course of the background's yarn, closing through +x.
void intarsiaCourses(const CellInputs& in, const intarsia::RowBlock& block, double scale, ChartCell& cell,
                     std::vector<char>& letter) {
    const int W = in.chart.width, H = in.chart.height;
    for (int k = 0; k < block.rows; ++k) {
        const int r = (block.first + k) % H;
        const CellGeometry g{&in.chart, &in.rows, &in.plan, &in.yarns[size_t(r)], 0};
        const std::vector<uint32_t> at = columnStarts(g, r, in.n, uint32_t(cell.pattern.points.size()));
        for (int c = 0; c < W; ++c)
            cell.loops[size_t(r) * size_t(W) + size_t(c)] =
                stitchLoop(in, r, c, cell.yarns, at[size_t(c)], at[size_t(c) + 1] - at[size_t(c)]);
        addCourse(in, r, 0, cell.yarns++, at, scale, cell, letter);
    }
}

// One area's serpentine over its block's rows, open (tails at both ends) or closed.
void intarsiaYarn(const CellInputs& in, const intarsia::RowBlock& block, size_t a, double scale, ChartCell& cell,
                  std::vector<char>& letter) {
    Pattern& p = cell.pattern;
    const int W = in.chart.width;
    const std::vector<intarsia::Place>& places = block.places[a];
    const uint32_t first = uint32_t(p.points.size());
    IntarsiaYarn yarn;
    for (int k = 0; k < block.rows; ++k) {
        const bool last = k + 1 == block.rows, rightwards = k % 2 == 0;
        SerpentineRow sr{places[size_t(k)], block.areas[a].colour, cell.yarns, block.first + k};
        sr.rightwards = rightwards;
        sr.turns = block.closed || !last;
        sr.startTail = !block.closed && k == 0;
        sr.endTail = !block.closed && last;
        if (sr.turns) {  // the next row goes the other way: it starts at the end this row stops at
            const intarsia::Place& above = places[size_t(k) + 1];
            sr.nextColumn = rightwards ? above.first + above.count - 1 : above.first;
            sr.nextIndex = above.index;
        }
        intarsiaRow(in, sr, scale, cell, yarn, letter);
    }
    const int shift = block.closed ? (places.back().first - places.front().first) / W : 0;
    intarsiaEdges(yarn, first, block.closed, shift, p);
    cell.anchors.insert(cell.anchors.end(), yarn.anchored.begin(), yarn.anchored.end());
    cell.floats.insert(cell.floats.end(), yarn.floats.begin(), yarn.floats.end());
    ++cell.yarns;
}

// Steps 5-6 for intarsia: each area's yarn a serpentine over its block's rows (chart_intarsia.hpp),
// closing through +y after the last row's turn when every row continues from the row below
// (vertical bands, a zigzag or a diagonal stripe), else open with a tail at each end; blocks of
// one colour as plain courses. Returns the palette letter of every vertex.
std::vector<char> buildIntarsia(const CellInputs& in, double scale, ChartCell& cell) {
    const Chart& chart = in.chart;
    const int W = chart.width, H = chart.height;
    // A loop per stitch, a turn per area and row (shorter than two loops, plus a loop per stitch
    // it is carried on) and two tails per area and block (each shorter than a loop), bounded first.
    const std::vector<intarsia::RowBlock> blocks = intarsia::rowBlocks(chart);
    uint64_t carried = 0;
    for (const intarsia::RowBlock& block : blocks)
        for (const std::vector<intarsia::Place>& places : block.places)
            for (size_t k = 1; k < places.size(); ++k)
                carried +=
                    uint64_t(std::abs(places[k].first - places[k - 1].first) +
                             std::abs(places[k].first + places[k].count - places[k - 1].first - places[k - 1].count));
    checkVertexCount(chart, (uint64_t(W) * uint64_t(H) * 5 + carried) * uint64_t(in.n));
    cell.loops.assign(size_t(W) * size_t(H), {});
    cell.yarns = 0;
    std::vector<char> letter;
    for (const intarsia::RowBlock& block : blocks) {
        if (block.areas.size() == 1 && !block.closed) {
            intarsiaCourses(in, block, scale, cell, letter);
            continue;
        }
        for (size_t a = 0; a < block.areas.size(); ++a) intarsiaYarn(in, block, a, scale, cell, letter);
    }
    return letter;
}

// Step 7: the colour layer, per loop (sRGB) and per vertex (linear).
void colourLayer(const Chart& chart, const std::vector<char>& letter, ChartCell& cell) {
    if (chart.colour.empty()) return;
    for (const StitchLoop& l : cell.loops) cell.colour.push_back(chart.palette.at(chart.colourAt(l.row, l.column)));
    std::map<char, glm::vec3> linear;
    for (const auto& [key, srgb] : chart.palette) {
        glm::vec3 c(0.f);
        for (int k = 0; k < 3; ++k) c[k] = float(util::srgbToLinear(srgb[size_t(k)] / 255.0));
        linear[key] = c;
    }
    for (const char c : letter) cell.pattern.colour.push_back(linear.at(c));
}

}  // namespace

ChartStacking chartStacking(const Chart& chart) {
    if (chart.colourwork != Colourwork::Intarsia) return {1, chart.height, false};
    const intarsia::Closing c = intarsia::closing(chart);
    return {c.times, c.rows, c.wandering};
}

std::string stackingWarning(const Chart& chart, const ChartStacking& stacking) {
    if (!stacking.wandering) return "";
    return "intarsia: the colour areas move round the period and, after the chart's " + std::to_string(chart.height) +
           " rows, arrive on other areas of their colour; each area's yarn comes back to itself after " +
           std::to_string(stacking.rows) + " rows, so the chart's repeat is knitted " + std::to_string(stacking.rows) +
           " rows tall (its rows " + std::to_string(stacking.times) + " times over)";
}

void checkStackedSize(const Chart& chart, const ChartStacking& stacking, int samplesPerStitch, uint64_t limit,
                      const std::string& why) {
    const uint64_t vertices = uint64_t(chart.width) * uint64_t(stacking.rows) * uint64_t(samplesPerStitch);
    if (!stacking.wandering || vertices <= limit) return;
    throw Error(chart.name + ": " + stackingWarning(chart, stacking) + ": " + std::to_string(stacking.rows) +
                " rows x " + std::to_string(chart.width) + " stitches at " + std::to_string(samplesPerStitch) +
                " samples per stitch make at least " + std::to_string(vertices) + " yarn vertices, more than " +
                std::to_string(limit) + " (" + why +
                "): chart a repeat in which fewer areas go round the period, or give the areas a row where they "
                "start");
}

ChartCell chartToCell(const Chart& chart, const ChartCellOptions& options) {
    if (!util::positiveFinite(options.radius)) throw Error("knitting chart: the yarn radius must be positive");
    if (options.samplesPerStitch < 8) throw Error("knitting chart: the samples per stitch must be >= 8");
    // Intarsia is knitted back and forth: when every row continues from the row below each yarn's
    // serpentine closes after an even number of rows, and once each area is back on itself
    // (chartStacking; motifs' yarns are open: any number).
    const bool isIntarsia = chart.colourwork == Colourwork::Intarsia;
    const ChartStacking stacking = chartStacking(chart);
    checkStackedSize(chart, stacking, options.samplesPerStitch, kMaxChartVertices,
                     "a chart is one period of the fabric");
    const Chart stacked = stacking.times > 1 ? intarsia::repeatRows(chart, stacking.times) : Chart{};
    const Chart& ch = stacking.times > 1 ? stacked : chart;
    const double s = options.radius / kModelRadius;  // metres per model unit
    ChartCell cell;
    cell.width = ch.width;
    cell.height = ch.height;
    cell.stacking = stacking;
    const std::vector<RowYarns> yarns = rowYarns(ch);
    const std::vector<Plan> plan = planLoops(ch);
    const RowLayout rows = rowLayout(ch, plan);
    const CellInputs in{ch, yarns, plan, rows, options.samplesPerStitch};
    const std::vector<std::vector<uint32_t>> starts =
        isIntarsia ? std::vector<std::vector<uint32_t>>{} : stitchRecord(in, cell);
    Pattern& p = cell.pattern;
    p.name = chart.name;
    p.stitchesPerPeriod = ch.width;
    p.rowsPerPeriod = ch.height;
    p.px = util::kTwoPi * ch.width * s;
    p.py = rows.period * s;
    p.radius = options.radius;
    const std::vector<char> letter = isIntarsia ? buildIntarsia(in, s, cell) : buildYarns(in, starts, s, cell);
    p.twist.assign(p.points.size(), 0.0);
    cell.restScale = liftedRestScale(cell, s, options.samplesPerStitch);
    // A chart stacked twice lists the floats of its first copy only (the second repeats them), so
    // every float's row is a row of the chart as written (Chart::rowLine, the warnings).
    cell.floats.erase(std::remove_if(cell.floats.begin(), cell.floats.end(),
                                     [&](const ChartFloat& f) { return f.row >= chart.height; }),
                      cell.floats.end());
    std::stable_sort(cell.floats.begin(), cell.floats.end(),
                     [](const ChartFloat& a, const ChartFloat& b) { return a.row < b.row; });
    colourLayer(ch, letter, cell);
    validatePattern(p, p.name);
    return cell;
}

}  // namespace knit
