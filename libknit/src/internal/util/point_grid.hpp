// point_grid.hpp (internal) — a uniform grid over a fixed set of 3D points for fixed-radius
// neighbour queries (binding's seam welder; reusable wherever nearby points are paired).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace knit::impl {

class PointGrid {
public:
    struct Neighbour {
        uint32_t index;   // into the points the grid was built from
        double distance;  // glm::distance(query, point)
    };

    // Point i lies in cell floor(points[i] / cellSize) (per coordinate). `cellSize` must be
    // positive and finite; a query radius of one cell size looks at the 3 x 3 x 3 cells around
    // the query's own.
    PointGrid(std::vector<glm::dvec3> points, double cellSize);

    // The points at distance <= radius (finite, >= 0) from `query` (the query itself when it is one of the
    // points), by ascending index. Candidates come from the cells within ceil(radius / cellSize)
    // (at least 1) of the query's cell, so the answer is exact unless rounding puts a point at
    // distance ~radius one cell farther; the cost grows with the cube of radius / cellSize.
    // `out` is cleared first.
    void within(const glm::dvec3& query, double radius, std::vector<Neighbour>& out) const;

    size_t size() const { return points_.size(); }
    const glm::dvec3& point(size_t i) const { return points_[i]; }

private:
    using Cell = std::array<int64_t, 3>;
    Cell cellOf(const glm::dvec3& p) const;
    // The points of cell c, as a range into order_ (empty when no point lies in it).
    std::pair<uint32_t, uint32_t> pointsIn(const Cell& c) const;

    double cellSize_;
    std::vector<glm::dvec3> points_;
    std::vector<Cell> cells_;        // occupied cells, ascending
    std::vector<uint32_t> offsets_;  // per occupied cell: its range into order_
    std::vector<uint32_t> order_;    // point indices by cell, ascending within a cell
};

}  // namespace knit::impl
