// binding_boundary.hpp (internal) — where a UV segment meets the boundary of a UV island: the
// locate phase asks whether a step between two located vertices leaves its island, the cut phase
// where a yarn crosses the boundary towards a cut neighbour.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "binding_pieces.hpp"
#include "knit/base_mesh.hpp"
#include "knit/uv_grid.hpp"

namespace knit::impl {

// A UV segment p -> q with the height and twist at both ends.
struct UvStep {
    glm::dvec2 p, q;
    double hp, hq, tp, tq;
};

// First crossing of the UV segment p -> q with a boundary edge of `island`, as a bound vertex on
// that edge with height and twist interpolated along the segment. None when p is already on the
// boundary (t ~ 0) or no boundary edge is crossed.
std::optional<BoundVertex> boundaryCrossing(const BaseMesh& mesh, const UvGrid& grid, uint32_t island,
                                            const UvStep& step);

// True when the UV segment p -> q between two vertices located in `island` passes outside the
// island on the way: over a gap, a hole or a notch of the UV layout narrower than the segment,
// where the surface is not continuous (the segment would be a chord through the air in 3D).
// The island's boundary edges crossed by the segment split it into pieces; a piece whose middle
// lies in no triangle of the island is outside. Pieces within `tol` of an end are ignored: a
// clamped end lies up to `tol` outside. Cells without boundary edges cost one lookup each.
// cp, cq: the grid cells of p and q. `ts`: scratch space.
bool leavesIsland(const BaseMesh& mesh, const UvGrid& grid, uint32_t island, glm::dvec2 p, glm::dvec2 q, glm::ivec2 cp,
                  glm::ivec2 cq, double tol, std::vector<double>& ts);

}  // namespace knit::impl
