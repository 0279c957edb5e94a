// binding_locate: point location of yarn vertices and the steps that leave their island.
#include <gtest/gtest.h>

#include "binding_inputs.hpp"
#include "binding/binding_locate.hpp"

namespace knit::impl {
namespace {

// The unit square of 3 x 2 quads without the top middle quad: a notch u in [1/3, 2/3], v >= 1/2.
BaseMesh notchedSquare() {
    BaseMesh m = hard::sheet(
        "notch", 3, 2, [](double s, double t) { return glm::dvec3(s, t, 0.0); },
        [](double s, double t) { return glm::dvec2(s, t); });
    const size_t quad = 1 * 3 + 1;  // (i, j) = (1, 1)
    m.faces.erase(m.faces.begin() + 2 * quad, m.faces.begin() + 2 * quad + 2);
    m.faceUvs.erase(m.faceUvs.begin() + 2 * quad, m.faceUvs.begin() + 2 * quad + 2);
    return m;
}

TEST(BindingLocate, clampsWithinToleranceAndCutsBeyond) {
    const BaseMesh mesh = test::unitSquare();
    const UvGrid grid = test::quarterGrid(mesh);
    const UvYarns yarns = test::uvYarns({{{0.5, 0.5}, {1.0 + 1e-4, 0.5}, {1.5, 0.5}}}, {0});
    const LocatedYarns located = locateYarns(mesh, grid, yarns, {1e-3});
    EXPECT_EQ(located.loc[0].status, LocateStatus::Inside);
    EXPECT_EQ(located.loc[1].status, LocateStatus::Clamped);
    EXPECT_EQ(located.loc[2].status, LocateStatus::Outside);
    EXPECT_EQ(located.clampedVertices, 1u);
    EXPECT_EQ(located.outsideVertices, 1u);
    EXPECT_TRUE(located.located(1));
    EXPECT_FALSE(located.located(2));
}

TEST(BindingLocate, stepAcrossANotchLeavesTheChart) {
    const BaseMesh mesh = notchedSquare();
    const UvGrid grid = test::quarterGrid(mesh);
    // Across the notch (v = 0.8), then below it (v = 0.3): both ends are located in the island.
    const UvYarns yarns = test::uvYarns({{{0.2, 0.8}, {0.8, 0.8}}, {{0.2, 0.3}, {0.8, 0.3}}}, {0, 0});
    const LocatedYarns located = locateYarns(mesh, grid, yarns, {1e-3});
    ASSERT_EQ(located.outsideVertices, 0u);
    EXPECT_EQ(located.leaves, (std::vector<uint8_t>{1, 0, 0, 0}));
}

TEST(BindingLocate, closingStepIsCheckedOnClosedYarnsOnly) {
    const BaseMesh mesh = notchedSquare();
    const UvGrid grid = test::quarterGrid(mesh);
    // Down the left arm, across below the notch, up the right arm; closing step: over the notch.
    const std::vector<glm::dvec2> ring = {{0.2, 0.8}, {0.2, 0.3}, {0.8, 0.3}, {0.8, 0.8}};
    const LocatedYarns closed = locateYarns(mesh, grid, test::uvYarns({ring}, {1}), {1e-3});
    EXPECT_EQ(closed.leaves, (std::vector<uint8_t>{0, 0, 0, 1}));
    const LocatedYarns open = locateYarns(mesh, grid, test::uvYarns({ring}, {0}), {1e-3});
    EXPECT_EQ(open.leaves, (std::vector<uint8_t>{0, 0, 0, 0}));
}

TEST(BindingLocate, yarnOfOneChartIsNotClampedFromInsideAnother) {
    const BaseMesh mesh = test::twoChartsSideBySide();
    const UvGrid grid = test::quarterGrid(mesh);
    ASSERT_EQ(grid.islandCount, 2u);
    // Just right of u = 1: inside the right island, within the tolerance of the left one.
    UvYarns yarns = test::uvYarns({{{0.9, 0.5}, {1.0 + 1e-4, 0.5}}}, {0});
    const LocatedYarns any = locateYarns(mesh, grid, yarns, {1e-3});
    EXPECT_EQ(any.loc[1].status, LocateStatus::Inside);
    EXPECT_EQ(grid.islandOfFace[any.loc[1].point.face], 1u);
    yarns.island = {0};
    const LocatedYarns leftOnly = locateYarns(mesh, grid, yarns, {1e-3});
    EXPECT_EQ(leftOnly.loc[0].status, LocateStatus::Inside);
    EXPECT_EQ(leftOnly.loc[1].status, LocateStatus::Outside);
    EXPECT_EQ(leftOnly.clampedVertices, 0u);
}

TEST(BindingLocate, emptyYarnsLocateNothing) {
    const BaseMesh mesh = test::unitSquare();
    const LocatedYarns located = locateYarns(mesh, test::quarterGrid(mesh), test::uvYarns({{}}, {0}), {1e-3});
    EXPECT_TRUE(located.leaves.empty());
    EXPECT_EQ(located.outsideVertices, 0u);
}

}  // namespace
}  // namespace knit::impl
