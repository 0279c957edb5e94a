// Intarsia colourwork in a periodic cell: the colour areas and the interlocking turns of their
// yarns at the boundaries (see chart_intarsia.hpp).
#include "chart_intarsia.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "util/math.hpp"

namespace knit::intarsia {
namespace {

// A turn's shape (model units): its far edge this far past the boundary (less than the inset, so
// a turn's far edge passes between the neighbour's foot and the boundary), the overshoot above
// and below the two feet (the band where two turns hook through each other), the depth of its
// near corners and of its far edge behind the work.
constexpr double kFarReach = 0.9;
constexpr double kOvershoot = 1.0;
constexpr double kNearDepth = 1.5;
constexpr double kFarDepth = 4.5;
// Where the boundary steps, the far edge crosses over this far above and below the bands where
// the neighbours' turns hook through it.
constexpr double kStepClear = 0.5;
// A tail: below its row's loop centres and behind the work as a stranded float (the stitches'
// lower legs and the heads below lie in front of it), its end this far short of the far boundary.
// A one-stitch area's tail lies higher, just above the head of the loop below (0.5 below the loop
// centres): lower down, behind that loop's legs, the anchored tail stayed where it was built while
// the area settled back, and the head below came out in front of the stitch (the diamond's tips
// lost their crossings with the loop below). On chart:intarsia-diamond every stitch keeps its
// crossings for drops 0 to 0.5, not for -0.5, 0.75, 1.0 or 2.5 (docs/charts.md, "Diagonals").
constexpr double kTailDrop = 2.5;
constexpr double kAloneTailDrop = 0.25;
constexpr double kTailDepth = 2.4;
constexpr double kTailClear = 2.0;

}  // namespace

std::vector<Area> areas(const Chart& chart, int row) {
    const int w = chart.width;
    auto colour = [&](int c) { return chart.colourAt(row, ((c % w) + w) % w); };
    int start = 0;
    while (start < w && colour(start) == colour(start - 1)) ++start;
    if (start == w) return {{colour(0), 0, w}};  // one colour: one area round the period
    std::vector<Area> out;
    for (int k = 0; k < w;) {
        Area a{colour(start + k), (start + k) % w, 0};
        for (; k < w && colour(start + k) == a.colour; ++k) ++a.count;
        out.push_back(a);
    }
    std::sort(out.begin(), out.end(), [](const Area& a, const Area& b) { return a.first < b.first; });
    return out;
}

namespace {

// How each area of a row continues into the next row's (`above`): the index of its continuation
// there and how far its first column moves, or nothing when the rows do not continue: a different
// number of areas, other colours, or a boundary whose move is ambiguous (`tie`). One colour
// continues into the same colour.
using Follow = std::vector<std::pair<int, int>>;
struct Continuation {
    std::optional<Follow> follow;
    std::optional<Tie> tie;  // the rows would continue but a boundary could move either way round
};

// Step 1: every boundary moves by at most kMaxMove columns, read cyclically from -kMaxMove (as
// since issue 25 round 5: the first shift of the areas that fits).
std::optional<Follow> followNear(const std::vector<Area>& below, const std::vector<Area>& above, int width) {
    const size_t n = below.size();
    auto step = [&](int from, int to) {  // cyclic, from -kMaxMove
        return ((to - from + kMaxMove) % width + width) % width - kMaxMove;
    };
    for (size_t s = 0; s < n; ++s) {
        Follow out;
        for (size_t i = 0; i < n; ++i) {
            const Area &a = below[i], &b = above[(i + s) % n];
            const int first = step(a.first, b.first), end = step(a.first + a.count, b.first + b.count);
            if (a.colour != b.colour || first > kMaxMove || end > kMaxMove || b.count != a.count + end - first) break;
            out.push_back({int((i + s) % n), first});
        }
        if (out.size() == n) return out;
    }
    return std::nullopt;
}

// A boundary's move from column `from` to `to`, the shorter way round the period (a move of half
// the width either way is a tie).
int shortest(int from, int to, int width) {
    const int m = ((to - from) % width + width) % width;
    return 2 * m > width ? m - width : m;
}

// Step 2: any move, each boundary the shorter way round; the shift of the areas whose largest move
// is smallest. A tie (a move of half the width, or two shifts as good) continues nothing: which way
// the yarn is carried is not drawn.
Continuation followFar(const std::vector<Area>& below, const std::vector<Area>& above, int width) {
    const size_t n = below.size();
    Continuation best;
    int bestCost = width, ties = 0;
    for (size_t s = 0; s < n; ++s) {
        Follow out;
        int cost = 0;
        std::optional<Tie> tie;
        for (size_t i = 0; i < n; ++i) {
            const Area &a = below[i], &b = above[(i + s) % n];
            const int first = shortest(a.first, b.first, width);
            const int end = shortest(a.first + a.count, b.first + b.count, width);
            if (a.colour != b.colour || b.count != a.count + end - first) break;
            const int boundary = 2 * std::abs(first) == width ? first : end;  // the tied one, if any
            if (!tie && 2 * std::abs(boundary) == width)
                tie = Tie{0, boundary == first ? a.first : a.first + a.count, std::abs(boundary)};
            cost = std::max({cost, std::abs(first), std::abs(end)});
            out.push_back({int((i + s) % n), first});
        }
        if (out.size() != n) continue;
        if (cost < bestCost) {
            best = {out, tie};
            bestCost = cost;
            ties = 0;
        } else if (cost == bestCost) {  // two shifts as far: the move goes either way
            ++ties;
        }
    }
    if (best.follow && ties > 0 && !best.tie) {
        best.tie = Tie{0, below.front().first, bestCost};
    }
    if (best.tie) best.follow.reset();
    return best;
}

Continuation follow(const std::vector<Area>& below, const std::vector<Area>& above, int width) {
    const size_t n = below.size();
    if (n != above.size()) return {};
    if (n == 1) return below == above ? Continuation{Follow{{0, 0}}, std::nullopt} : Continuation{};
    if (std::optional<Follow> near = followNear(below, above, width)) return {near, std::nullopt};
    return followFar(below, above, width);
}

// Area a's places along `count` rows from row `first`, following `into`.
std::vector<Place> track(const std::vector<std::vector<Area>>& rows, const std::vector<std::optional<Follow>>& into,
                         int first, int count, int a) {
    const int H = int(rows.size());
    const Area& start = rows[size_t(first % H)][size_t(a)];
    std::vector<Place> out{{start.first, start.count, a}};
    for (int k = 1; k < count; ++k) {
        const Place& p = out.back();
        const auto [index, move] = (*into[size_t((first + k) % H)])[size_t(p.index)];
        out.push_back({p.first + move, rows[size_t((first + k) % H)][size_t(index)].count, index});
    }
    return out;
}

}  // namespace

std::vector<RowBlock> rowBlocks(const Chart& chart) {
    const int H = chart.height;
    std::vector<std::vector<Area>> rows(static_cast<size_t>(H));
    for (int r = 0; r < H; ++r) rows[size_t(r)] = areas(chart, r);
    std::vector<std::optional<Follow>> into;  // into[r]: how row r - 1 continues into row r
    into.reserve(size_t(H));
    for (int r = 0; r < H; ++r)
        into.push_back(follow(rows[size_t((r + H - 1) % H)], rows[size_t(r)], chart.width).follow);
    int start = 0;
    while (start < H && into[size_t(start)]) ++start;
    if (start == H) {  // every row continues: one closed block (each yarn back to itself?)
        RowBlock b{0, H, rows[0], {}, true, true};
        for (size_t a = 0; a < rows[0].size(); ++a) {
            b.places.push_back(track(rows, into, 0, H + 1, int(a)));
            const Place& back = b.places.back().back();
            b.returns = b.returns && back.index == int(a) && (back.first - int(rows[0][a].first)) % chart.width == 0;
        }
        return {b};
    }
    std::vector<RowBlock> out;
    for (int k = 0; k < H; ++k) {
        const int r = (start + k) % H;
        if (out.empty() || !into[size_t(r)]) out.push_back({r, 0, rows[size_t(r)], {}, false, true});
        ++out.back().rows;
    }
    for (RowBlock& b : out)
        for (size_t a = 0; a < b.areas.size(); ++a) b.places.push_back(track(rows, into, b.first, b.rows, int(a)));
    return out;
}

std::optional<Tie> tiedMove(const Chart& chart, int row) {
    const int H = chart.height, r = ((row % H) + H) % H;
    std::optional<Tie> tie = follow(areas(chart, (r + H - 1) % H), areas(chart, r), chart.width).tie;
    if (tie) tie->row = r;
    return tie;
}

Closing closing(const Chart& chart) {
    const RowBlock block = rowBlocks(chart).front();
    if (!block.closed) return {1, chart.height, false};
    // Step 1: after the chart's rows each area arrives on area places[a].back().index; the rows
    // close every yarn after the least common multiple of that permutation's cycle lengths
    // (a cyclic shift of the areas: at most their count).
    int cycles = 1;
    for (size_t a = 0; a < block.places.size(); ++a) {
        int length = 1;
        for (size_t at = size_t(block.places[a].back().index); at != a; at = size_t(block.places[at].back().index))
            ++length;
        cycles = cycles / std::gcd(cycles, length) * length;
    }
    // Step 2: each serpentine turns on alternate rows, so it closes after an even number of rows.
    const int times = (cycles * chart.height) % 2 == 0 ? cycles : 2 * cycles;
    return {times, times * chart.height, cycles > 1};
}

Chart repeatRows(const Chart& chart, int times) {
    Chart out = chart;
    auto repeat = [times](auto& v) {
        const auto once = v;
        for (int k = 1; k < times; ++k) v.insert(v.end(), once.begin(), once.end());
    };
    repeat(out.kind);
    repeat(out.op);
    repeat(out.rowLine);
    repeat(out.firstSource);
    repeat(out.colour);
    for (int k = 1; k < times; ++k)
        for (ChartCable c : chart.cables) {
            c.row += k * chart.height;
            out.cables.push_back(c);
        }
    out.height = times * chart.height;
    return out;
}

TurnPoints turnPoints(const Turn& turn, double spacing) {
    const double nearX = turn.boundary + turn.side * kBoundaryInset, farX = turn.boundary - turn.side * kFarReach;
    const double step = turn.boundaryAbove - turn.boundary;
    const double low = turn.from.y - kOvershoot, high = turn.to.y + kOvershoot;
    std::vector<glm::dvec3> corners{turn.from, {nearX, low, -kNearDepth}, {farX, low, -kFarDepth}};
    const bool held = std::abs(step) > 1.5 * util::kTwoPi;  // carried two stitches on or more
    if (step != 0) {  // carried a column on: up at this row's boundary, over, up at the next row's
        corners.push_back({farX, turn.from.y + kOvershoot + kStepClear, -kFarDepth});
        corners.push_back({farX + step, turn.to.y - kOvershoot - kStepClear, -kFarDepth});
    }
    corners.push_back({farX + step, high, -kFarDepth});
    corners.push_back({nearX + step, high, -kNearDepth});
    corners.push_back(turn.to);
    std::vector<double> along{0.0};  // arc length at each corner
    for (size_t k = 1; k < corners.size(); ++k)
        along.push_back(along.back() + glm::length(corners[k] - corners[k - 1]));
    const int count = std::max(6, int(std::lround(along.back() / spacing)));
    TurnPoints out;
    size_t leg = 1;
    for (int i = 0; i < count; ++i) {
        const double s = along.back() * i / count;
        while (leg + 1 < along.size() && along[leg] < s) ++leg;
        const double u = (s - along[leg - 1]) / std::max(1e-12, along[leg] - along[leg - 1]);
        out.points.push_back(corners[leg - 1] + u * (corners[leg] - corners[leg - 1]));
        const bool crossover = step != 0 && s >= along[3] && s <= along[4];  // corners 3-4
        out.held.push_back(held && crossover);
        out.crossover.push_back(crossover);
    }
    return out;
}

std::vector<glm::dvec3> tailPoints(const glm::dvec3& foot, double rowY, int inward, int stitches, bool alone,
                                   double spacing) {
    // Behind the work at the depth of a float behind its row's stitches (and its height, or just
    // above the head below for a stitch alone), reaching to kTailClear short of the far boundary
    // (which lies 2 pi stitches - kBoundaryInset from the foot).
    const double reach = util::kTwoPi * stitches - kBoundaryInset - kTailClear;
    const double y = rowY - (alone ? kAloneTailDrop : kTailDrop);
    const std::vector<glm::dvec3> corners{
        foot, {foot.x + inward * 1.0, y, -kTailDepth}, {foot.x + inward * reach, y, -kTailDepth}};
    std::vector<glm::dvec3> out;
    for (size_t k = 1; k < corners.size(); ++k) {
        const double length = glm::length(corners[k] - corners[k - 1]);
        const int count = std::max(2, int(std::lround(length / spacing)));
        for (int i = 1; i <= count; ++i)
            out.push_back(corners[k - 1] + (double(i) / count) * (corners[k] - corners[k - 1]));
    }
    return out;
}

}  // namespace knit::intarsia
