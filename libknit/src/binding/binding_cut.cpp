// binding_cut.cpp — binding phase 2: yarns into pieces, cut at the UV boundary (see
// binding_cut.hpp).
#include "binding_cut.hpp"

#include <optional>

#include "binding_boundary.hpp"

namespace knit::impl {
namespace {

// Cuts one yarn at a time into pieces, appended to the result. Indices are yarn-local.
class YarnCutter {
public:
    YarnCutter(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, const LocatedYarns& located,
               CutResult& out)
        : mesh_(mesh), grid_(grid), yarns_(yarns), located_(located), out_(out) {}

    void cut(size_t y) {
        b_ = yarns_.offsets[y];
        n_ = yarns_.offsets[y + 1] - b_;
        if (n_ == 0) return;
        const bool closed = yarns_.closed[y] != 0;
        // A closed yarn is walked from a run boundary; without one it is a single closed piece.
        size_t breakAt = 0;
        if (closed) {
            const std::optional<size_t> first = firstBreak();
            if (!first) {
                addClosedPiece();
                return;
            }
            breakAt = *first;
        }
        const GhostVertex noGhost;
        const GhostVertex& startGhost = closed || yarns_.ghosts.empty() ? noGhost : yarns_.ghosts[y][0];
        const GhostVertex& endGhost = closed || yarns_.ghosts.empty() ? noGhost : yarns_.ghosts[y][1];
        // Runs of joined located vertices become pieces.
        cur_ = Piece{};
        for (size_t s = 0; s < n_; ++s) {
            const size_t i = (breakAt + s) % n_;
            const size_t prev = (i + n_ - 1) % n_;
            if (!located(i)) {
                finish(prev, target(i));
                continue;
            }
            if (cur_.count > 0 && !joined(prev, i)) finish(prev, target(i));
            if (cur_.count == 0) {
                // Entering from a cut: start with the boundary crossing towards the previous vertex.
                const bool cutBefore = closed || s > 0;
                begin(i, cutBefore ? target(prev) : startGhost, cutBefore || startGhost.present);
            }
            ++cur_.count;
        }
        // The last run of a closed yarn ends at the break it started from; an open yarn's last
        // run may end at a ghost.
        if (closed) finish((breakAt + n_ - 1) % n_, target(breakAt));
        else finish(n_ - 1, endGhost);
    }

private:
    bool located(size_t i) const { return located_.located(b_ + i); }
    uint32_t island(size_t i) const { return grid_.islandOfFace[located_.loc[b_ + i].point.face]; }
    // Consecutive vertices i -> j = i+1 stay joined when both are located in the same island and
    // the step between them does not leave the island.
    bool joined(size_t i, size_t j) const {
        return located(i) && located(j) && island(i) == island(j) && !located_.leaves[b_ + i];
    }
    // The first vertex of a closed yarn that is not joined to its predecessor, if any.
    std::optional<size_t> firstBreak() const {
        for (size_t i = 0; i < n_; ++i)
            if (!joined((i + n_ - 1) % n_, i)) return i;
        return std::nullopt;
    }
    void addClosedPiece() {
        Piece piece;
        piece.yarnBegin = uint32_t(b_);
        piece.yarnSize = piece.count = uint32_t(n_);
        piece.closed = true;
        out_.pieces.push_back(piece);
    }
    // Yarn vertex i as the far end of a segment towards a cut neighbour.
    GhostVertex target(size_t i) const {
        return GhostVertex{true, yarns_.uv[b_ + i], yarns_.height[b_ + i], yarns_.twist[b_ + i]};
    }
    // Crossing from located vertex i towards a cut neighbour (a yarn vertex or a ghost).
    std::optional<BoundVertex> crossingTowards(size_t i, const GhostVertex& to) {
        const size_t p = b_ + i;
        const UvStep step{yarns_.uv[p], to.uv, yarns_.height[p], to.height, yarns_.twist[p], to.twist};
        std::optional<BoundVertex> x = boundaryCrossing(mesh_, grid_, island(i), step);
        if (x) {
            x->origin = uint32_t(p);
            ++out_.boundaryVertices;
        }
        return x;
    }
    // Starts a piece at vertex i; entered from a cut (`fromCut`), it gets a head on the boundary.
    void begin(size_t i, const GhostVertex& before, bool fromCut) {
        cur_.yarnBegin = uint32_t(b_);
        cur_.yarnSize = uint32_t(n_);
        cur_.start = uint32_t(i);
        if (fromCut) {
            cur_.head = crossingTowards(i, before);
            cur_.boundaryEnd[0] = true;
        }
    }
    // Ends the current piece at vertex lastIdx, with a tail towards `beyond` when present; a
    // piece of a single point is dropped.
    void finish(size_t lastIdx, const GhostVertex& beyond) {
        if (cur_.count == 0) return;
        if (beyond.present) {
            cur_.tail = crossingTowards(lastIdx, beyond);
            cur_.boundaryEnd[1] = true;
        }
        if (cur_.size() >= 2) out_.pieces.push_back(cur_);
        else ++out_.droppedVertices;
        cur_ = Piece{};
    }

    const BaseMesh& mesh_;
    const UvGrid& grid_;
    const UvYarns& yarns_;
    const LocatedYarns& located_;
    CutResult& out_;
    size_t b_ = 0, n_ = 0;  // the yarn being cut: first vertex, size
    Piece cur_;             // the piece being built
};

}  // namespace

CutResult cutYarns(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, const LocatedYarns& located) {
    CutResult out;
    YarnCutter cutter(mesh, grid, yarns, located, out);
    for (size_t y = 0; y < yarns.yarnCount(); ++y) cutter.cut(y);
    return out;
}

}  // namespace knit::impl
