// scene_budget.hpp (internal) — the pipeline's size estimates: each big stage's memory from its
// counts, checked against the scene's MemoryBudget before the stage allocates.
#pragma once
#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/budget.hpp"
#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/tiling.hpp"

namespace knit::impl {

// Bytes the stages keep per element (their vectors plus the working copies while they run);
// deliberately generous: an estimate that refuses a bit early beats swapping.
constexpr double kBytesPerCell = 64;         // UV grid cell, its triangle list share, tile mark
constexpr double kBytesPerGridEntry = 20;    // (cell, triangle) pair while sorting + its list entry
constexpr double kBytesPerYarnVertex = 160;  // UV yarns, binding, mapped yarns and normals
constexpr double kBytesPerPlyPoint = 48;     // ply point and radial direction
constexpr double kBytesPerWalkedVertex = 5;  // a view's region build: stitch's walk (id + visited mark)

// The UV grid: cells spanned by the mesh's UV range at the placement's cell size. Driven by
// --repeats (or the mesh's size at the pattern's physical size).
void checkGridBudget(const BaseMesh& mesh, const PatternPlacement& placement, bool physicalSize,
                     const MemoryBudget& budget);

// Tiling and stitching over `coveredCells` cells spanning `cellSpan`: tile marks and yarn
// vertices (every tile emits the pattern's vertices). Driven by --repeats, or by a pattern
// vertex far outside its cell (which widens the reach).
// With `regionOnly` (a view's region build) every tiled vertex costs only stitch's walk
// (kBytesPerWalkedVertex); the yarns kept are checked by checkRegionYarnBudget once counted.
void checkTilingBudget(const Pattern& pattern, size_t coveredCells, glm::ivec2 cellSpan, const TileReach& reach,
                       bool physicalSize, const MemoryBudget& budget, bool regionOnly = false);

// A view's region build: the yarn vertices through its region (UV yarns, binding, mapped yarns
// and normals), counted by the stitch walk before any of them is allocated.
void checkRegionYarnBudget(uint64_t vertices, bool physicalSize, const MemoryBudget& budget);

// The plies of the mapped yarns: their length / pitch x samples per turn x plies.
// Driven by --samples-per-turn and --ply-pitch.
void checkPlyBudget(const MappedYarns& yarns, const PlyOptions& resolved, const MemoryBudget& budget);
// The same for `samples` resampled centre points, known exactly (a stored Animator state).
void checkPlyBudget(double samples, const PlyOptions& resolved, const MemoryBudget& budget);

}  // namespace knit::impl
