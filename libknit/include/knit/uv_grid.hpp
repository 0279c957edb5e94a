// knit/uv_grid.hpp — sparse grid over UV space: which triangles touch which pattern cell.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "knit/base_mesh.hpp"

namespace knit {

struct UvGridOptions {
    glm::dvec2 cellSize{1.0 / 32.0};  // UV size of one cell (= one pattern period)
    // Refuse grids whose bounding box holds more cells than this (absurd repeats).
    uint64_t maxCells = uint64_t(1) << 28;
    // Refuse grids whose triangle lists would hold more (cell, triangle) entries than this:
    // triangles far larger than a cell, stacked on each other, list each triangle in every cell
    // of its box (a 40 KB file can ask for 10^8 entries). See uvGridEntryBound.
    uint64_t maxEntries = uint64_t(1) << 26;
};

// Cells are indexed (i, j) with cell (i, j) = [i*cu, (i+1)*cu) x [j*cv, (j+1)*cv).
// Only cells that some triangle touches are stored (sparse); the triangle-cell overlap is
// conservative: a triangle touching a cell, even at a corner, is listed in it.
struct UvGrid {
    glm::dvec2 cellSize{0.0};
    glm::ivec2 minCell{0}, dims{0};        // bounding box of touched cells
    std::vector<int32_t> cellSlot;         // dims.x*dims.y, -1 = empty, else index into cells
    std::vector<glm::ivec2> cells;         // touched cells, in row-major order
    std::vector<uint32_t> triOffsets{0};   // per touched cell: range into triangles
    std::vector<uint32_t> triangles;       // triangle ids, ascending per cell
    std::vector<uint32_t> edgeOffsets{0};  // per touched cell: range into boundaryEdges
    std::vector<uint32_t> boundaryEdges;   // UV boundary half-edges (3*face + corner), per cell
    std::vector<uint32_t> islandOfFace;    // UV island (connected UV island) of each face, 0-based
    // Islands, numbered in the order of their lowest face (a zero-UV-area triangle that shares no
    // UV edge with another triangle is an island of its own).
    uint32_t islandCount = 0;
    // Pairs (a < b) of islands whose UV triangles overlap (exact test; touching is no overlap).
    // Every island that overlaps another is in some pair (not every overlapping pair is listed:
    // at most islandCount pairs). With any, the pipeline tiles and binds each island on its own
    // (knit/scene.hpp), so every island gets its knit.
    std::vector<glm::uvec2> overlappingIslands;
    std::vector<int8_t> faceOrientation;  // +1 counter-clockwise, -1 mirrored, 0 zero-area UV
    size_t degenerateUvFaces = 0;         // zero-area UV triangles (never own a point)
    // Triangles on the folded-over side of an island that folds over itself in UV: across a fold
    // edge both triangles lie on the same side of it, so the island covers that UV region twice
    // and a point there is bound to whichever layer holds the lowest triangle (the other layer
    // gets no yarns there). The side of the island with the smaller UV area counts as folded.
    // Independent of 3D winding (a face wound the other way is no fold). Reported, not refused.
    size_t foldedUvFaces = 0;
    uint32_t foldedUvFaceExample = UINT32_MAX;  // lowest folded triangle, UINT32_MAX when none

    glm::ivec2 cellOf(glm::dvec2 uv) const;
    // -1 when the cell is empty or outside the bounding box.
    int32_t slotOf(glm::ivec2 cell) const;
};

UvGrid buildUvGrid(const BaseMesh& mesh, const UvGridOptions& options);

// Upper bound of the (cell, triangle) entries buildUvGrid lists for this cell size: the cells
// of each non-degenerate UV triangle's bounding box, summed (saturates at UINT64_MAX). O(faces),
// no allocation: the size estimate before the grid is built.
uint64_t uvGridEntryBound(const BaseMesh& mesh, glm::dvec2 cellSize);

enum class LocateStatus : uint8_t { Inside, Clamped, Outside };
struct LocateResult {
    LocateStatus status = LocateStatus::Outside;
    SurfacePoint point;
    double distance = 0;  // UV distance to the triangle for Clamped
};

// Point location with exact orientation predicates. A point on a shared edge or vertex belongs
// to the lowest-numbered (non-degenerate) triangle that contains it, so every point has exactly
// one owner. A point in no triangle but within `tolerance` (UV units) of one goes to the closest
// triangle with clamped barycentrics; farther out it is Outside. Coordinates are never nudged.
// `hint`: a triangle to try first (the previous vertex's along a yarn). A point strictly inside
// the hint is given to it without scanning the cell: the same owner as the scan unless UV islands
// overlap, where it keeps a yarn on the island it is already on.
// `island`: only triangles of this island are considered (kAnyIsland: all).
constexpr uint32_t kAnyIsland = UINT32_MAX;
LocateResult locatePoint(const BaseMesh& mesh, const UvGrid& grid, glm::dvec2 uv, double tolerance,
                         uint32_t hint = UINT32_MAX, uint32_t island = kAnyIsland);

}  // namespace knit
