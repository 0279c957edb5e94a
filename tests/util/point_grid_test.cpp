// point_grid: fixed-radius neighbour queries over a uniform grid of points.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include "util/point_grid.hpp"

namespace knit::impl {
namespace {

std::vector<uint32_t> indicesWithin(const PointGrid& grid, glm::dvec3 q, double radius) {
    std::vector<PointGrid::Neighbour> near;
    grid.within(q, radius, near);
    std::vector<uint32_t> out;
    for (const PointGrid::Neighbour& n : near) out.push_back(n.index);
    return out;
}

TEST(PointGrid, pointAtExactlyTheRadiusIsFound) {
    const PointGrid grid({{0, 0, 0}, {0.5, 0, 0}, {0.5000001, 0, 0}}, 0.5);
    std::vector<PointGrid::Neighbour> near;
    grid.within({0, 0, 0}, 0.5, near);
    ASSERT_EQ(near.size(), 2u);
    EXPECT_EQ(near[1].index, 1u);
    EXPECT_EQ(near[1].distance, 0.5);
}

TEST(PointGrid, queryFindsItselfAndCoincidentPoints) {
    const PointGrid grid({{1, 2, 3}, {1, 2, 3}, {4, 5, 6}}, 1.0);
    EXPECT_EQ(indicesWithin(grid, grid.point(1), 0.0), (std::vector<uint32_t>{0, 1}));
}

TEST(PointGrid, neighboursComeByAscendingIndexWhateverTheirCells) {
    // Points in cells -1, 0 and +1 along each axis, inserted out of cell order.
    const PointGrid grid({{0.9, 0, 0}, {-0.1, 0, 0}, {0.1, 0.1, 0.1}, {0, -0.9, 0}, {0, 0, 0.95}}, 1.0);
    EXPECT_EQ(indicesWithin(grid, {0, 0, 0}, 1.0), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
}

TEST(PointGrid, negativeCoordinatesFloorToTheirOwnCell) {
    // -0.05 lies in cell -1 and +0.05 in cell 0: still neighbours.
    const PointGrid grid({{-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}}, 0.1);
    EXPECT_EQ(indicesWithin(grid, grid.point(0), 0.2), (std::vector<uint32_t>{0, 1}));
}

TEST(PointGrid, radiusLargerThanACellLooksFurther) {
    const PointGrid grid({{0, 0, 0}, {2.5, 0, 0}, {0, -3.5, 0}}, 1.0);
    EXPECT_EQ(indicesWithin(grid, {0, 0, 0}, 1.0), (std::vector<uint32_t>{0}));
    EXPECT_EQ(indicesWithin(grid, {0, 0, 0}, 2.6), (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(indicesWithin(grid, {0, 0, 0}, 3.5), (std::vector<uint32_t>{0, 1, 2}));
}

TEST(PointGrid, farFromTheOriginCellIndicesDoNotWrap) {
    // Cell indices ~4e11, beyond 32 bits: the neighbour across a cell boundary is found, the point
    // 2^32 cells away (the same cell under a 32-bit index) is not.
    const double cell = 2.5e-4;
    const glm::dvec3 far(1e8, 1e8, 1e8);
    const PointGrid grid({far, far - glm::dvec3(2e-4, 0, 0), far + glm::dvec3(cell * 4294967296.0, 0, 0)}, cell);
    EXPECT_EQ(indicesWithin(grid, far, cell), (std::vector<uint32_t>{0, 1}));
}

TEST(PointGrid, emptyGridAnswersNothing) {
    const PointGrid grid({}, 1.0);
    EXPECT_EQ(grid.size(), 0u);
    EXPECT_TRUE(indicesWithin(grid, {0, 0, 0}, 1.0).empty());
}

TEST(PointGrid, answersEqualABruteForceScan) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<glm::dvec3> points(500);
    for (glm::dvec3& p : points) p = {u(rng), u(rng), u(rng)};
    const PointGrid grid(points, 0.15);
    for (size_t q = 0; q < points.size(); q += 7)
        for (double radius : {0.05, 0.15, 0.4}) {
            std::vector<uint32_t> expected;
            for (uint32_t i = 0; i < points.size(); ++i)
                if (glm::distance(points[q], points[i]) <= radius) expected.push_back(i);
            EXPECT_EQ(indicesWithin(grid, points[q], radius), expected) << q << " " << radius;
        }
}

}  // namespace
}  // namespace knit::impl
