// point_grid.cpp — points sorted into uniform cells; neighbours from the cells around a query
// (see point_grid.hpp).
#include "point_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

namespace knit::impl {
namespace {

// A floored coordinate as a cell index; far-out (and NaN) coordinates are clamped so that the
// neighbouring cells stay representable.
int64_t cellIndex(double v) {
    constexpr double kLimit = 4.0e18;
    if (std::isnan(v)) return 0;
    return int64_t(std::clamp(std::floor(v), -kLimit, kLimit));
}

}  // namespace

PointGrid::PointGrid(std::vector<glm::dvec3> points, double cellSize)
    : cellSize_(cellSize), points_(std::move(points)) {
    assert(cellSize > 0 && std::isfinite(cellSize));
    // Sort the point indices by (cell, index), then list each occupied cell once.
    std::vector<Cell> cellOfPoint(points_.size());
    for (size_t i = 0; i < points_.size(); ++i) cellOfPoint[i] = cellOf(points_[i]);
    order_.resize(points_.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
        return cellOfPoint[a] != cellOfPoint[b] ? cellOfPoint[a] < cellOfPoint[b] : a < b;
    });
    for (uint32_t k = 0; k < order_.size(); ++k)
        if (k == 0 || cellOfPoint[order_[k]] != cells_.back()) {
            cells_.push_back(cellOfPoint[order_[k]]);
            offsets_.push_back(k);
        }
    offsets_.push_back(uint32_t(order_.size()));
}

PointGrid::Cell PointGrid::cellOf(const glm::dvec3& p) const {
    const glm::dvec3 c = p / cellSize_;
    return {cellIndex(c.x), cellIndex(c.y), cellIndex(c.z)};
}

std::pair<uint32_t, uint32_t> PointGrid::pointsIn(const Cell& c) const {
    const auto it = std::lower_bound(cells_.begin(), cells_.end(), c);
    if (it == cells_.end() || *it != c) return {0, 0};
    const size_t slot = size_t(it - cells_.begin());
    return {offsets_[slot], offsets_[slot + 1]};
}

void PointGrid::within(const glm::dvec3& query, double radius, std::vector<Neighbour>& out) const {
    assert(radius >= 0 && std::isfinite(radius));
    out.clear();
    const int64_t rings = std::max<int64_t>(1, int64_t(std::ceil(radius / cellSize_)));
    const Cell c = cellOf(query);
    // Every point of the cells around the query's, filtered by distance.
    for (int64_t dz = -rings; dz <= rings; ++dz)
        for (int64_t dy = -rings; dy <= rings; ++dy)
            for (int64_t dx = -rings; dx <= rings; ++dx) {
                const auto [begin, end] = pointsIn({c[0] + dx, c[1] + dy, c[2] + dz});
                for (uint32_t k = begin; k < end; ++k) {
                    const uint32_t i = order_[k];
                    const double d = glm::distance(query, points_[i]);
                    if (!(d <= radius)) continue;
                    out.push_back({i, d});
                }
            }
    // Deterministic order: by index.
    std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) { return a.index < b.index; });
}

}  // namespace knit::impl
