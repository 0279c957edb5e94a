// binding_cut: located yarns into pieces, with a vertex exactly on the UV boundary at each cut.
#include <gtest/gtest.h>

#include "binding/binding_cut.hpp"
#include "binding_inputs.hpp"

namespace knit::impl {
namespace {

struct CutCase {
    BaseMesh mesh;
    UvGrid grid;
    UvYarns yarns;
    LocatedYarns located;

    CutCase(BaseMesh m, UvYarns y) : mesh(std::move(m)), grid(test::quarterGrid(mesh)), yarns(std::move(y)) {
        located = locateYarns(mesh, grid, yarns, {1e-6});
    }
    CutResult cut() const { return cutYarns(mesh, grid, yarns, located); }
    glm::dvec2 uvOf(const BoundVertex& v) const {
        const glm::uvec3 t = mesh.faceUvs[v.face];
        return v.bary.x * mesh.uvs[t.x] + v.bary.y * mesh.uvs[t.y] + v.bary.z * mesh.uvs[t.z];
    }
};

TEST(BindingCut, cutInsertsVertexExactlyOnBoundary) {
    // 0.5 and 0.9 inside, 1.2 and 1.5 outside: one piece of two vertices plus the crossing at u = 1.
    const CutCase c(test::unitSquare(), test::uvYarns({{{0.5, 0.5}, {0.9, 0.5}, {1.2, 0.5}, {1.5, 0.5}}}, {0}));
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 1u);
    const Piece& pc = r.pieces[0];
    EXPECT_EQ(pc.start, 0u);
    EXPECT_EQ(pc.count, 2u);
    EXPECT_FALSE(pc.head);
    ASSERT_TRUE(pc.tail);
    EXPECT_FALSE(pc.boundaryEnd[0]);
    EXPECT_TRUE(pc.boundaryEnd[1]);
    EXPECT_EQ(r.boundaryVertices, 1u);
    // The crossing lies on a boundary edge: one barycentric is exactly 0, the UV is (1, 0.5).
    const BoundVertex& x = *pc.tail;
    EXPECT_EQ(std::min({x.bary.x, x.bary.y, x.bary.z}), 0.0);
    EXPECT_DOUBLE_EQ(c.uvOf(x).x, 1.0);
    EXPECT_DOUBLE_EQ(c.uvOf(x).y, 0.5);
    // Height interpolated along 0.9 -> 1.2 (heights 0.001, 0.002) at a third of the way.
    EXPECT_NEAR(x.height, 0.001 + 0.001 / 3, 1e-15);
}

TEST(BindingCut, vertexOnTheBoundaryGetsNoCrossingAndAloneIsDropped) {
    // The first vertex lies on u = 1: the crossing towards 1.5 starts at it (none is inserted);
    // a piece of that one point is dropped.
    const CutCase c(test::unitSquare(), test::uvYarns({{{1.0, 0.5}, {1.5, 0.5}}}, {0}));
    const CutResult r = c.cut();
    EXPECT_TRUE(r.pieces.empty());
    EXPECT_EQ(r.boundaryVertices, 0u);
    EXPECT_EQ(r.droppedVertices, 1u);
}

TEST(BindingCut, closedYarnWithoutCutStaysOneClosedPiece) {
    const CutCase c(test::unitSquare(), test::uvYarns({{{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.8}, {0.2, 0.8}}}, {1}));
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 1u);
    EXPECT_TRUE(r.pieces[0].closed);
    EXPECT_EQ(r.pieces[0].count, 4u);
    EXPECT_EQ(r.pieces[0].size(), 4u);
    EXPECT_FALSE(r.pieces[0].boundaryEnd[0] || r.pieces[0].boundaryEnd[1]);
}

TEST(BindingCut, closedYarnIsWalkedFromItsFirstCut) {
    // Vertex 1 is outside: the loop becomes one open piece 2, 3, 0 with crossings at both ends.
    const CutCase c(test::unitSquare(), test::uvYarns({{{0.8, 0.5}, {1.3, 0.5}, {0.8, 0.8}, {0.5, 0.6}}}, {1}));
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 1u);
    const Piece& pc = r.pieces[0];
    EXPECT_FALSE(pc.closed);
    EXPECT_EQ(pc.start, 2u);
    EXPECT_EQ(pc.count, 3u);
    EXPECT_TRUE(pc.head && pc.tail);
    EXPECT_DOUBLE_EQ(c.uvOf(*pc.head).x, 1.0);
    EXPECT_DOUBLE_EQ(c.uvOf(*pc.tail).x, 1.0);
    EXPECT_EQ(r.boundaryVertices, 2u);
}

TEST(BindingCut, ghostBeyondOpenEndGivesBoundaryEnd) {
    // The yarn ends inside; its ghost (the next tiled vertex, not in the tiling) lies outside.
    UvYarns yarns = test::uvYarns({{{0.5, 0.5}, {0.9, 0.5}}}, {0});
    yarns.ghosts = {{GhostVertex{}, GhostVertex{true, {1.1, 0.5}, 0.0, 0.0}}};
    const CutCase c(test::unitSquare(), yarns);
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 1u);
    EXPECT_FALSE(r.pieces[0].boundaryEnd[0]);
    EXPECT_TRUE(r.pieces[0].boundaryEnd[1]);
    ASSERT_TRUE(r.pieces[0].tail);
    EXPECT_DOUBLE_EQ(c.uvOf(*r.pieces[0].tail).x, 1.0);
}

TEST(BindingCut, chartChangeSplitsTheYarnAtTheSharedBoundary) {
    const CutCase c(test::twoChartsSideBySide(),
                    test::uvYarns({{{0.6, 0.5}, {0.8, 0.5}, {1.2, 0.5}, {1.4, 0.5}}}, {0}));
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 2u);
    EXPECT_EQ(r.pieces[0].count, 2u);
    EXPECT_TRUE(r.pieces[0].tail && !r.pieces[0].head);
    EXPECT_EQ(r.pieces[1].start, 2u);
    EXPECT_TRUE(r.pieces[1].head && !r.pieces[1].tail);
    EXPECT_DOUBLE_EQ(c.uvOf(*r.pieces[0].tail).x, 1.0);
    EXPECT_DOUBLE_EQ(c.uvOf(*r.pieces[1].head).x, 1.0);
    EXPECT_EQ(c.grid.islandOfFace[r.pieces[1].head->face], 1u);
}

TEST(BindingCut, stepFlaggedAsLeavingSplitsTheYarnWithoutCrossing) {
    // Inside the square all along, but the locate phase flagged step 1 -> 2 as leaving the island:
    // two pieces with boundary ends there and no crossing vertex (no boundary edge is crossed).
    CutCase c(test::unitSquare(), test::uvYarns({{{0.2, 0.5}, {0.4, 0.5}, {0.6, 0.5}, {0.8, 0.5}}}, {0}));
    c.located.leaves[1] = 1;
    const CutResult r = c.cut();
    ASSERT_EQ(r.pieces.size(), 2u);
    EXPECT_TRUE(r.pieces[0].boundaryEnd[1] && !r.pieces[0].tail);
    EXPECT_TRUE(r.pieces[1].boundaryEnd[0] && !r.pieces[1].head);
    EXPECT_EQ(r.pieces[0].size() + r.pieces[1].size(), 4u);
    EXPECT_EQ(r.boundaryVertices, 0u);
}

}  // namespace
}  // namespace knit::impl
