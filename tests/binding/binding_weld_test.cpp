// binding_weld: cut ends that meet again in object space with continuing tangents are welded.
#include <gtest/gtest.h>

#include "binding_inputs.hpp"
#include "binding/binding_weld.hpp"

namespace knit::impl {
namespace {

const glm::dvec3 kX(1, 0, 0), kY(0, 1, 0);

WeldEnd end(glm::dvec3 p, glm::dvec3 outward) { return WeldEnd{true, p, outward}; }

WeldResult weld(const std::vector<WeldEnd>& ends, double tolerance = 1.0, double minCos = 0.5) {
    return weldEnds(ends, {tolerance, minCos});
}

TEST(BindingWeld, weldPicksNearestContinuingEnd) {
    // End 0 points +x; ends 1 and 2 come back (-x), 2 is nearer.
    const WeldResult r = weld({end({0, 0, 0}, kX), end({0.5, 0, 0}, -kX), end({0.2, 0.1, 0}, -kX)});
    EXPECT_EQ(r.partner, (std::vector<int64_t>{2, -1, 0}));
    EXPECT_EQ(r.weldedEnds, 2u);
}

TEST(BindingWeld, weldRefusesOpposingTangents) {
    // Both ends point +x: the yarn would fold back on itself.
    EXPECT_EQ(weld({end({0, 0, 0}, kX), end({0.1, 0, 0}, kX)}).weldedEnds, 0u);
    // At right angles (cos 0 < 0.5) too; accepted once minCos allows it.
    EXPECT_EQ(weld({end({0, 0, 0}, kX), end({0.1, 0, 0}, kY)}).weldedEnds, 0u);
    EXPECT_EQ(weld({end({0, 0, 0}, kX), end({0.1, 0, 0}, kY)}, 1.0, 0.0).weldedEnds, 2u);
}

TEST(BindingWeld, weldReachesExactlyTheTolerance) {
    EXPECT_EQ(weld({end({0, 0, 0}, kX), end({0.25, 0, 0}, -kX)}, 0.25).weldedEnds, 2u);
    EXPECT_EQ(weld({end({0, 0, 0}, kX), end({0.25, 0, 0}, -kX)}, 0.2499).weldedEnds, 0u);
}

TEST(BindingWeld, weldTiesGoToTheLowerEndIds) {
    // Ends 0 and 2 are both at distance 0.5 from end 1: the pair (0, 1) comes first.
    const WeldResult r = weld({end({0.5, 0, 0}, -kX), end({0, 0, 0}, kX), end({0.5, 0, 0}, -kX)});
    EXPECT_EQ(r.partner, (std::vector<int64_t>{1, 0, -1}));
}

TEST(BindingWeld, eachEndWeldsOnceNearestPairsFirst) {
    // 0 -> 1 nearest (0.1), then 2 could take 1 (0.15) but 1 is taken: 2 welds with 3.
    const WeldResult r =
        weld({end({0, 0, 0}, kX), end({0.1, 0, 0}, -kX), end({0.25, 0, 0}, kX), end({0.9, 0, 0}, -kX)});
    EXPECT_EQ(r.partner, (std::vector<int64_t>{1, 0, 3, 2}));
    EXPECT_EQ(r.weldedEnds, 4u);
}

TEST(BindingWeld, absentEndsAndZeroToleranceWeldNothing) {
    std::vector<WeldEnd> ends = {end({0, 0, 0}, kX), WeldEnd{}, end({0, 0, 0}, -kX)};
    ends[1].outward = -kX;  // not present: ignored even where it would fit
    EXPECT_EQ(weld(ends).partner, (std::vector<int64_t>{2, -1, 0}));
    EXPECT_EQ(weld(ends, 0.0).partner, (std::vector<int64_t>{-1, -1, -1}));
    EXPECT_TRUE(weld({}).partner.empty());
}

TEST(BindingWeld, endsOnEitherSideOfACellBoundaryWeld) {
    // -0.1 and +0.1 lie in cells -1 and 0 of a grid of tolerance-sized cells.
    EXPECT_EQ(weld({end({-0.1, -0.1, -0.1}, kX), end({0.1, 0.1, 0.1}, -kX)}).weldedEnds, 2u);
    // Far from the origin too (cell indices beyond 32 bits).
    const glm::dvec3 far(1e6, -2e6, 3e6);
    EXPECT_EQ(weld({end(far, kX), end(far + glm::dvec3(1e-7, 0, 0), -kX)}, 1e-6).weldedEnds, 2u);
}

TEST(BindingWeld, pieceEndsPointOutwardFromTheNextToEndVertex) {
    // Unit square, 1 x 1 quad: face 0 = (0,0), (1,0), (1,1). A piece of two run vertices with a
    // head; a closed piece has no ends; an open piece's non-boundary end is absent.
    const BaseMesh mesh = test::unitSquare(1);
    const std::vector<glm::dvec3> normals = test::upNormals(mesh);
    const std::vector<LocateResult> loc = {test::locatedAt(0, {0.5, 0.5, 0.0}), test::locatedAt(0, {0.25, 0.5, 0.25})};
    const std::vector<double> height = {0.0, 0.0}, twist = {0.0, 0.0};
    const PieceVertices vertices{loc.data(), height.data(), twist.data()};
    Piece open;
    open.yarnSize = open.count = 2;
    open.head = BoundVertex{0, {0.0, 1.0, 0.0}, 0.0, 0.0};  // (1, 0)
    open.boundaryEnd[0] = true;
    Piece closed = open;
    closed.closed = true;
    const std::vector<WeldEnd> ends = pieceEnds(RestSurface{mesh, normals}, {open, closed}, vertices);
    ASSERT_EQ(ends.size(), 4u);
    EXPECT_TRUE(ends[0].present);
    EXPECT_FALSE(ends[1].present || ends[2].present || ends[3].present);
    EXPECT_EQ(ends[0].position, glm::dvec3(1, 0, 0));
    // From the first run vertex (0.5, 0) to the head (1, 0): +x.
    EXPECT_NEAR(glm::distance(ends[0].outward, kX), 0.0, 1e-15);
}

}  // namespace
}  // namespace knit::impl
