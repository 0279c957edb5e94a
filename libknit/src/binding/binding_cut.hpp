// binding_cut.hpp (internal) — binding phase 2: split the located yarns into pieces where they
// leave the UV region, with a vertex exactly on the UV boundary at every cut end.
#pragma once
#include <cstddef>
#include <vector>

#include "binding_locate.hpp"
#include "binding_pieces.hpp"
#include "knit/base_mesh.hpp"
#include "knit/stitch.hpp"
#include "knit/uv_grid.hpp"

namespace knit::impl {

struct CutResult {
    std::vector<Piece> pieces;    // in yarn order; within a yarn in walking order
    size_t boundaryVertices = 0;  // crossing vertices inserted on the UV boundary
    size_t droppedVertices = 0;   // located but isolated: a piece of a single point
};

// Each yarn is split at unlocated vertices, at island changes and at steps that leave their island
// (located.leaves). A piece entered from or left towards a cut neighbour (a yarn vertex or the
// yarn's ghost beyond an open end) gets the vertex where the segment towards that neighbour first
// crosses the island's boundary, and that end is marked as a boundary end. A closed yarn without
// any cut stays one closed piece; one with cuts starts at its first cut.
CutResult cutYarns(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, const LocatedYarns& located);

}  // namespace knit::impl
