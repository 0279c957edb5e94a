// binding_chain.cpp — binding phase 4: pieces into yarns along the welds (see binding_chain.hpp).
// First the plan, piece by piece (serial, cheap): which pieces in which direction, and whether a
// junction vertex repeats the previous one (dropped); then every vertex is copied to its place
// in parallel.
#include "binding_chain.hpp"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace knit::impl {
namespace {

// A piece's vertices in one yarn of the output.
struct Segment {
    uint32_t piece;
    bool reversed, dropFirst, dropLast;
    size_t outStart;  // output index of its first emitted vertex
};

// Plans the yarns: segments, the binding's offsets and closed flags, the loop and end counts.
class ChainPlanner {
public:
    ChainPlanner(const RestSurface& rest, const std::vector<Piece>& pieces, const PieceVertices& vertices,
                 const std::vector<int64_t>& partner, const ChainOptions& options, ChainResult& out)
        : rest_(rest),
          pieces_(pieces),
          vertices_(vertices),
          partner_(partner),
          options_(options),
          out_(out),
          used_(pieces.size(), 0) {
        segments_.reserve(pieces.size());
    }

    void plan() {
        for (size_t pi = 0; pi < pieces_.size(); ++pi) {
            if (used_[pi] || !pieces_[pi].closed) continue;
            used_[pi] = 1;
            addSegment(pi, false, false);
            closeYarn(true);
        }
        for (size_t pi = 0; pi < pieces_.size(); ++pi)
            for (int e = 0; e < 2; ++e)
                if (!used_[pi] && partner_[2 * pi + e] < 0) closeYarn(walkChain(pi, e));
        for (size_t pi = 0; pi < pieces_.size(); ++pi)
            if (!used_[pi]) closeYarn(walkChain(pi, 0));
    }

    const std::vector<Segment>& segments() const { return segments_; }
    size_t vertexCount() const { return outCount_; }

private:
    // First (last = false) or last vertex of a segment, in the segment's direction, at rest.
    glm::dvec3 endPosition(const Segment& g, bool last) const {
        return rest_.position(vertices_.end(pieces_[g.piece], last, g.reversed));
    }
    void addSegment(size_t pi, bool reversed, bool dropFirst) {
        const Segment g{uint32_t(pi), reversed, dropFirst, false, outCount_};
        outCount_ += pieces_[pi].size() - (dropFirst ? 1 : 0);
        segments_.push_back(g);
    }
    // Walks from piece `first`, entered at end `enterEnd`, along the welds; true when the chain
    // comes back to a piece it used (a closed loop).
    bool walkChain(size_t first, int enterEnd) {
        size_t pi = first;
        int enter = enterEnd;
        bool firstPiece = true;
        for (;;) {
            used_[pi] = 1;
            const bool reversed = enter == 1;
            const glm::dvec3 head = rest_.position(vertices_.end(pieces_[pi], false, reversed));
            const bool drop =
                !firstPiece && glm::distance(endPosition(segments_.back(), true), head) < options_.dedupeDistance;
            addSegment(pi, reversed, drop);
            firstPiece = false;
            const int64_t next = partner_[2 * pi + (1 - enter)];
            if (next < 0) return false;
            pi = size_t(next / 2);
            enter = int(next % 2);
            if (used_[pi]) {
                dropClosingVertex();
                return true;
            }
        }
    }
    // Back at the start of a loop: the last vertex repeating the first is dropped.
    void dropClosingVertex() {
        Segment& lastSeg = segments_.back();
        const Segment& firstSeg = segments_[yarnFirstSeg_];
        const size_t yarnSize = outCount_ - firstSeg.outStart;
        if (yarnSize > 2 &&
            glm::distance(endPosition(lastSeg, true), endPosition(firstSeg, false)) < options_.dedupeDistance) {
            lastSeg.dropLast = true;
            --outCount_;
        }
    }
    void closeYarn(bool closed) {
        out_.binding.offsets.push_back(uint32_t(outCount_));
        out_.binding.closed.push_back(closed ? 1 : 0);
        if (closed) ++out_.closedLoops;
        else out_.openEnds += 2;
        yarnFirstSeg_ = segments_.size();
    }

    const RestSurface& rest_;
    const std::vector<Piece>& pieces_;
    const PieceVertices& vertices_;
    const std::vector<int64_t>& partner_;
    const ChainOptions& options_;
    ChainResult& out_;
    std::vector<uint8_t> used_;
    std::vector<Segment> segments_;
    size_t outCount_ = 0;      // vertices planned so far
    size_t yarnFirstSeg_ = 0;  // first segment of the yarn being planned
};

// Copies every segment's vertices to its place, segments in parallel.
void fillBinding(const std::vector<Segment>& segments, size_t vertexCount, const std::vector<Piece>& pieces,
                 const PieceVertices& vertices, Binding& out) {
    tbb::parallel_invoke([&] { out.face.resize(vertexCount); }, [&] { out.bary.resize(vertexCount); },
                         [&] { out.height.resize(vertexCount); }, [&] { out.twist.resize(vertexCount); },
                         [&] { out.colour.resize(vertices.colour ? vertexCount : 0); },
                         [&] { out.source.resize(vertices.source ? vertexCount : 0); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, segments.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
            const Segment& g = segments[k];
            const Piece& pc = pieces[g.piece];
            const size_t n = pc.size();
            size_t o = g.outStart;
            for (size_t s = g.dropFirst ? 1 : 0; s < n - (g.dropLast ? 1 : 0); ++s, ++o) {
                const BoundVertex v = vertices.at(pc, g.reversed ? n - 1 - s : s);
                out.face[o] = v.face;
                out.bary[o] = glm::dvec2(v.bary.y, v.bary.z);
                out.height[o] = v.height;
                out.twist[o] = v.twist;
                if (vertices.colour) out.colour[o] = vertices.colour[v.origin];
                if (vertices.source) out.source[o] = vertices.source[v.origin];
            }
        }
    });
}

}  // namespace

ChainResult chainPieces(const RestSurface& rest, const std::vector<Piece>& pieces, const PieceVertices& vertices,
                        const std::vector<int64_t>& partner, const ChainOptions& options) {
    ChainResult out;
    ChainPlanner planner(rest, pieces, vertices, partner, options, out);
    planner.plan();
    fillBinding(planner.segments(), planner.vertexCount(), pieces, vertices, out.binding);
    return out;
}

}  // namespace knit::impl
