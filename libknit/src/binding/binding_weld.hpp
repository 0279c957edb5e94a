// binding_weld.hpp (internal) — binding phase 3: weld cut ends that meet again in object space
// (across UV seams, around cylinders) with continuing tangents.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "binding_pieces.hpp"

namespace knit::impl {

// One end of a piece: end 2p is piece p's first vertex, 2p+1 its last.
struct WeldEnd {
    bool present = false;      // a boundary end of an open piece (only those may weld)
    glm::dvec3 position{0.0};  // at rest
    glm::dvec3 outward{0.0};   // unit direction from the piece's next-to-end vertex (0 if they coincide)
};

// The two ends of every piece, evaluated on the rest surface.
std::vector<WeldEnd> pieceEnds(const RestSurface& rest, const std::vector<Piece>& pieces,
                               const PieceVertices& vertices);

struct WeldOptions {
    double tolerance = 0;  // object-space distance (metres); <= 0: nothing welds
    double minCos = 0.5;   // cosine between the continuing tangents (a.outward, -b.outward) required
};

struct WeldResult {
    std::vector<int64_t> partner;  // per end: the end it is welded to, or -1
    size_t weldedEnds = 0;         // 2 per weld
};

// Every pair of present ends within the tolerance whose tangents continue is a candidate; the
// candidates are taken nearest first (ties: lower end ids first), each end welding at most once.
WeldResult weldEnds(const std::vector<WeldEnd>& ends, const WeldOptions& options);

}  // namespace knit::impl
