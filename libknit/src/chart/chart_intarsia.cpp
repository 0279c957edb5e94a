// Intarsia colourwork in a periodic cell: the colour areas and the interlocking turns of their
// yarns at the boundaries (see chart_intarsia.hpp).
#include "chart_intarsia.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

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

}  // namespace

std::vector<Area> areas(const Chart& chart) {
    const int w = chart.width;
    auto colour = [&](int c) { return chart.colourAt(0, ((c % w) + w) % w); };
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

Chart evenRows(const Chart& chart) {
    if (chart.height % 2 == 0) return chart;
    Chart twice = chart;
    auto repeat = [](auto& v) { v.insert(v.end(), v.begin(), v.end()); };
    repeat(twice.kind);
    repeat(twice.op);
    repeat(twice.rowLine);
    repeat(twice.firstSource);
    repeat(twice.colour);
    for (ChartCable c : chart.cables) {
        c.row += chart.height;
        twice.cables.push_back(c);
    }
    twice.height = 2 * chart.height;
    return twice;
}

std::vector<glm::dvec3> turnPoints(const Turn& turn, double spacing) {
    const double nearX = turn.boundary + turn.side * kBoundaryInset, farX = turn.boundary - turn.side * kFarReach;
    const double low = turn.from.y - kOvershoot, high = turn.to.y + kOvershoot;
    const std::vector<glm::dvec3> corners{turn.from,
                                          {nearX, low, -kNearDepth},
                                          {farX, low, -kFarDepth},
                                          {farX, high, -kFarDepth},
                                          {nearX, high, -kNearDepth},
                                          turn.to};
    std::vector<double> along{0.0};  // arc length at each corner
    for (size_t k = 1; k < corners.size(); ++k)
        along.push_back(along.back() + glm::length(corners[k] - corners[k - 1]));
    const int count = std::max(6, int(std::lround(along.back() / spacing)));
    std::vector<glm::dvec3> out;
    size_t leg = 1;
    for (int i = 0; i < count; ++i) {
        const double s = along.back() * i / count;
        while (leg + 1 < along.size() && along[leg] < s) ++leg;
        const double u = (s - along[leg - 1]) / std::max(1e-12, along[leg] - along[leg - 1]);
        out.push_back(corners[leg - 1] + u * (corners[leg] - corners[leg - 1]));
    }
    return out;
}

}  // namespace knit::intarsia
