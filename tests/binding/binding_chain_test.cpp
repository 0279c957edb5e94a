// binding_chain: pieces chained along their welds into the binding's yarns.
#include <gtest/gtest.h>

#include "binding/binding_chain.hpp"
#include "binding_inputs.hpp"

namespace knit::impl {
namespace {

// Yarn vertices placed by hand on triangle 0 of a one-quad unit square, (0,0), (1,0), (1,1):
// vertex k at (x, y) with x >= y; its twist is k, so the output shows which vertex went where.
struct ChainCase {
    BaseMesh mesh = test::unitSquare(1);
    std::vector<glm::dvec3> normals = test::upNormals(mesh);
    std::vector<LocateResult> loc;
    std::vector<double> height, twist;
    std::vector<Piece> pieces;

    explicit ChainCase(const std::vector<glm::dvec2>& points) {
        for (const glm::dvec2& p : points) {
            loc.push_back(test::locatedAt(0, {1.0 - p.x, p.x - p.y, p.y}));
            height.push_back(0.0);
            twist.push_back(double(twist.size()));
        }
    }
    // Vertices [start, start + count) of one yarn of all the vertices, as an open piece.
    void piece(uint32_t start, uint32_t count, bool closed = false) {
        Piece pc;
        pc.yarnSize = uint32_t(loc.size());
        pc.start = start;
        pc.count = count;
        pc.closed = closed;
        pieces.push_back(pc);
    }
    ChainResult chain(const std::vector<int64_t>& partner) const {
        return chainPieces(RestSurface{mesh, normals}, pieces, {loc.data(), height.data(), twist.data()}, partner,
                           {1e-6});
    }
};

TEST(BindingChain, chainClosesLoopWhenEndsWeld) {
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}, {0.8, 0.3}, {0.6, 0.5}});
    c.piece(0, 2);
    c.piece(2, 2);
    // Last of piece 0 -> first of piece 1, last of piece 1 -> first of piece 0.
    const ChainResult r = c.chain({3, 2, 1, 0});
    EXPECT_EQ(r.binding.offsets, (std::vector<uint32_t>{0, 4}));
    EXPECT_EQ(r.binding.closed, (std::vector<uint8_t>{1}));
    EXPECT_EQ(r.binding.twist, (std::vector<double>{0, 1, 2, 3}));
    EXPECT_EQ(r.closedLoops, 1u);
    EXPECT_EQ(r.openEnds, 0u);
}

TEST(BindingChain, chainDropsJunctionAndClosingVerticesThatRepeat) {
    // Vertex 3 repeats vertex 2 (where the pieces meet), vertex 5 repeats vertex 0 (closing).
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}, {0.8, 0.3}, {0.8, 0.3}, {0.6, 0.5}, {0.2, 0.1}});
    c.piece(0, 3);
    c.piece(3, 3);
    const ChainResult r = c.chain({3, 2, 1, 0});
    EXPECT_EQ(r.binding.twist, (std::vector<double>{0, 1, 2, 4}));
    EXPECT_EQ(r.binding.closed, (std::vector<uint8_t>{1}));
}

TEST(BindingChain, chainReversesPieceEnteredAtItsLastEnd) {
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}, {0.8, 0.3}, {0.6, 0.5}});
    c.piece(0, 2);
    c.piece(2, 2);
    // Last of piece 0 welded to last of piece 1: piece 1 is walked backwards; the chain is open.
    const ChainResult r = c.chain({-1, 3, -1, 1});
    EXPECT_EQ(r.binding.twist, (std::vector<double>{0, 1, 3, 2}));
    EXPECT_EQ(r.binding.closed, (std::vector<uint8_t>{0}));
    EXPECT_EQ(r.openEnds, 2u);
    EXPECT_EQ(r.closedLoops, 0u);
}

TEST(BindingChain, closedPiecesComeFirstThenOpenChains) {
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}, {0.8, 0.3}, {0.6, 0.5}, {0.7, 0.6}});
    c.piece(0, 2);
    c.piece(2, 3, true);
    const ChainResult r = c.chain({-1, -1, -1, -1});
    EXPECT_EQ(r.binding.offsets, (std::vector<uint32_t>{0, 3, 5}));
    EXPECT_EQ(r.binding.closed, (std::vector<uint8_t>{1, 0}));
    EXPECT_EQ(r.binding.twist, (std::vector<double>{2, 3, 4, 0, 1}));
    EXPECT_EQ(r.closedLoops, 1u);
    EXPECT_EQ(r.openEnds, 2u);
}

TEST(BindingChain, pieceWeldedToItselfIsALoop) {
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}, {0.8, 0.3}});
    c.piece(0, 3);
    const ChainResult r = c.chain({1, 0});
    EXPECT_EQ(r.binding.twist, (std::vector<double>{0, 1, 2}));
    EXPECT_EQ(r.binding.closed, (std::vector<uint8_t>{1}));
}

TEST(BindingChain, twoVertexLoopKeepsItsRepeatedVertex) {
    // A closing vertex is only dropped from loops of more than two vertices.
    ChainCase c({{0.2, 0.1}, {0.2, 0.1}});
    c.piece(0, 2);
    const ChainResult r = c.chain({1, 0});
    EXPECT_EQ(r.binding.twist, (std::vector<double>{0, 1}));
    EXPECT_EQ(r.closedLoops, 1u);
}

TEST(BindingChain, boundVerticesKeepFaceBarycentricsAndHeight) {
    ChainCase c({{0.2, 0.1}, {0.5, 0.1}});
    c.height = {0.003, 0.004};
    c.piece(0, 2);
    c.pieces[0].head = BoundVertex{1, {0.5, 0.25, 0.25}, 0.002, -1.0};
    const ChainResult r = c.chain({-1, -1});
    ASSERT_EQ(r.binding.vertexCount(), 3u);
    EXPECT_EQ(r.binding.face, (std::vector<uint32_t>{1, 0, 0}));
    EXPECT_EQ(r.binding.bary[0], glm::dvec2(0.25, 0.25));  // (b1, b2)
    EXPECT_EQ(r.binding.bary[1], glm::dvec2(0.1, 0.1));
    EXPECT_EQ(r.binding.height, (std::vector<double>{0.002, 0.003, 0.004}));
    EXPECT_EQ(r.binding.twist, (std::vector<double>{-1, 0, 1}));
}

}  // namespace
}  // namespace knit::impl
