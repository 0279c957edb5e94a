// binding_locate.hpp (internal) — binding phase 1: locate every yarn vertex on the base mesh and
// flag the steps between located vertices that leave their UV island.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "binding_pieces.hpp"
#include "knit/base_mesh.hpp"
#include "knit/stitch.hpp"
#include "knit/uv_grid.hpp"

namespace knit::impl {

struct LocateOptions {
    // A point outside every triangle but within this UV distance of one is clamped onto it.
    double toleranceUv = 0;
};

struct LocatedYarns {
    struct Free {
        void operator()(LocateResult* p) const { std::free(p); }
    };
    // Per yarn vertex: where it lies (Outside: cut). Allocated without initialization: every
    // entry is constructed by locateYarns in parallel (a serial value-initialization of ~48 bytes
    // per vertex would cost as much as half the locating).
    std::unique_ptr<LocateResult[], Free> loc;
    // Per yarn vertex i: the step i -> i+1 (last -> first on closed yarns) joins two vertices
    // located in one island but passes outside the island on the way (see leavesIsland).
    std::vector<uint8_t> leaves;
    size_t clampedVertices = 0;  // outside every triangle, within the tolerance
    size_t outsideVertices = 0;  // in no triangle and beyond the tolerance (cut)

    bool located(size_t i) const { return loc[i].status != LocateStatus::Outside; }
    // The located vertices as pieces read them (heights and twists from `yarns`).
    PieceVertices vertices(const UvYarns& yarns) const {
        return {loc.get(), yarns.height.data(), yarns.twist.data(),
                yarns.colour.empty() ? nullptr : yarns.colour.data(),
                yarns.source.size() == yarns.vertexCount() ? yarns.source.data() : nullptr};
    }
};

// Yarns in parallel, each walked in order with the previous vertex's triangle as the hint
// (deterministic for any thread count). A yarn tiled for one island (yarns.island) is located on
// that island only and is not clamped onto it from inside another island.
LocatedYarns locateYarns(const BaseMesh& mesh, const UvGrid& grid, const UvYarns& yarns, const LocateOptions& options);

}  // namespace knit::impl
