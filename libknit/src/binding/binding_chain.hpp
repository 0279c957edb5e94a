// binding_chain.hpp (internal) — binding phase 4: chain the pieces along their welds into the
// binding's yarns.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "binding_pieces.hpp"
#include "knit/binding.hpp"

namespace knit::impl {

struct ChainOptions {
    // Where two chained pieces meet, a first vertex within this rest-pose distance of the
    // previous piece's last vertex repeats it and is dropped (so is a loop's closing vertex).
    double dedupeDistance = 0;
};

struct ChainResult {
    Binding binding;
    size_t closedLoops = 0;
    size_t openEnds = 0;  // 2 per open yarn
};

// Yarns in this order: closed pieces alone; chains walked from each unwelded end (pieces in
// order of their first unwelded end; a piece entered at its last end is reversed); then the
// remaining pieces, all of whose ends are welded, as loops. A chain that returns to its start is
// a closed loop. `partner`: per piece end (2p first, 2p+1 last) the end it is welded to, or -1.
ChainResult chainPieces(const RestSurface& rest, const std::vector<Piece>& pieces, const PieceVertices& vertices,
                        const std::vector<int64_t>& partner, const ChainOptions& options);

}  // namespace knit::impl
