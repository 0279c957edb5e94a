// From a stitch chart to an initial periodic yarn cell: one course per row, one loop per stitch,
// heights that give every crossing its over/under by construction (see knit/chart_topology.hpp).
#include "knit/chart_topology.hpp"

#include <algorithm>
#include <cmath>

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

double sign(StitchKind k) { return k == StitchKind::Knit ? 1.0 : -1.0; }
double smooth(double a, double b, double x) {  // 0 at a, 1 at b (either order)
    const double u = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return u * u * (3 - 2 * u);
}
int wrap(int i, int n) { return ((i % n) + n) % n; }

// What the row above does to the loop (row, column): the column of the loop pulled through it,
// and whether its head moves in a front cross.
struct Above {
    int column = 0;
    bool front = true;
};
Above rowAbove(const Chart& chart, int row, int column) {
    const int up = wrap(row + 1, chart.height);
    for (const ChartCable& c : chart.cables) {
        if (c.row != up || column < c.column || column >= c.column + c.left + c.right) continue;
        for (int p = c.column; p < c.column + c.left + c.right; ++p)
            if (chart.sourceColumn(up, p) == column) return {p, c.front};
    }
    return {column, true};
}

// Step 1: the stitch record (which loop is pulled through which).
std::vector<StitchLoop> stitchLoops(const Chart& chart, int samples) {
    std::vector<StitchLoop> loops;
    for (int r = 0; r < chart.height; ++r)
        for (int c = 0; c < chart.width; ++c) {
            StitchLoop l;
            l.row = r;
            l.column = c;
            l.first = uint32_t((r * chart.width + c) * samples);
            l.count = uint32_t(samples);
            l.kind = chart.at(r, c);
            l.sourceColumn = chart.sourceColumn(r, c);
            l.headShift = rowAbove(chart, r, c).column - c;
            loops.push_back(l);
        }
    return loops;
}

// Step 2: where each row sits (rows below a cable row are stretched by kCableLift).
struct RowLayout {
    std::vector<double> y;        // y of each row's loop centres
    std::vector<bool> stretched;  // the row above has a cable
    double period = 0;
};
RowLayout rowLayout(const Chart& chart) {
    RowLayout rows;
    for (int r = 0; r < chart.height; ++r) {
        const int up = wrap(r + 1, chart.height);
        const bool cable =
            std::any_of(chart.cables.begin(), chart.cables.end(), [&](const ChartCable& c) { return c.row == up; });
        rows.y.push_back(rows.period);
        rows.stretched.push_back(cable);
        rows.period += kRowPitch + (cable ? kCableLift : 0.0);
    }
    return rows;
}

// Step 3: one vertex of a loop at parameter t, in model units.
glm::dvec3 loopPoint(const Chart& chart, const RowLayout& rows, const StitchLoop& l, double t) {
    const double at = std::abs(t);
    // Plane: the plain-knit curve; the upper part lifted and moved by a cable of the row above.
    const double upper = rows.stretched[size_t(l.row)] ? smooth(kShift1, kShift0, at) : 0.0;
    const double x = util::kTwoPi * (l.column + l.headShift * upper) + t + kLoopWidth * std::sin(2 * t);
    const double y = rows.y[size_t(l.row)] + kLoopHeight * std::cos(t) + kCableLift * upper;
    // Height: the upper half follows the stitch pulled through this loop, the lower half this
    // stitch; at the feet the neighbouring column's kind takes over half-way.
    const Above above = rowAbove(chart, l.row, l.column);
    const double up = sign(chart.at(wrap(l.row + 1, chart.height), above.column));
    const double neighbour = sign(chart.at(l.row, wrap(l.column + (t < 0 ? -1 : 1), chart.width)));
    const double low = sign(l.kind) + 0.5 * (neighbour - sign(l.kind)) * smooth(util::kPi - kFootBlend, util::kPi, at);
    const double s = up + (low - up) * smooth(kLegSwitch0, kLegSwitch1, at);
    double z = -kDepth * std::cos(2 * t) * s;
    // Cable legs, where they cross: the left-moving ones in front for a front cross.
    if (l.headShift != 0) {
        const double bump = std::sin(util::kPi * upper);
        z += ((l.headShift < 0) == above.front ? 1.0 : -1.0) * kCableDepth * kDepth * bump;
    }
    return {x, y, z};
}

// The loop parameter of sample i of n: uniform, or dense around |t| = pi / 2 on stretched rows.
double loopParameter(const RowLayout& rows, const StitchLoop& l, int i, int n) {
    const double u = -util::kPi + util::kTwoPi * i / n;
    return rows.stretched[size_t(l.row)] ? u + kWarp * std::sin(2 * u) : u;
}

}  // namespace

ChartCell chartToCell(const Chart& chart, const ChartCellOptions& options) {
    if (!util::positiveFinite(options.radius)) throw Error("knitting chart: the yarn radius must be positive");
    if (options.samplesPerStitch < 8) throw Error("knitting chart: the samples per stitch must be >= 8");
    const int n = options.samplesPerStitch;
    const double s = options.radius / kModelRadius;  // metres per model unit
    ChartCell cell;
    cell.width = chart.width;
    cell.height = chart.height;
    cell.loops = stitchLoops(chart, n);
    Pattern& p = cell.pattern;
    p.name = chart.name;
    p.stitchesPerPeriod = chart.width;
    p.rowsPerPeriod = chart.height;
    p.px = util::kTwoPi * chart.width * s;
    const RowLayout rows = rowLayout(chart);
    p.py = rows.period * s;
    p.radius = options.radius;
    // Step 4: the vertices, loop by loop along each course; the course closes through +x.
    for (const StitchLoop& l : cell.loops)
        for (int i = 0; i < n; ++i) p.points.push_back(loopPoint(chart, rows, l, loopParameter(rows, l, i, n)) * s);
    p.twist.assign(p.points.size(), 0.0);
    const uint32_t perCourse = uint32_t(chart.width * n);
    for (int r = 0; r < chart.height; ++r) {
        const uint32_t first = uint32_t(r) * perCourse;
        for (uint32_t i = 0; i + 1 < perCourse; ++i) p.edges.push_back({first + i, first + i + 1, 0, 0});
        p.edges.push_back({first + perCourse - 1, first, 1, 0});
    }
    // Step 5: the colour layer, per loop (sRGB) and per vertex of the loop (linear).
    if (!chart.colour.empty())
        for (const StitchLoop& l : cell.loops) {
            const std::array<uint8_t, 3> srgb =
                chart.palette.at(chart.colour[size_t(l.row) * size_t(chart.width) + size_t(l.column)]);
            cell.colour.push_back(srgb);
            glm::vec3 linear(0.f);
            for (int k = 0; k < 3; ++k) linear[k] = float(util::srgbToLinear(srgb[size_t(k)] / 255.0));
            p.colour.insert(p.colour.end(), l.count, linear);
        }
    validatePattern(p, p.name);
    return cell;
}

}  // namespace knit
