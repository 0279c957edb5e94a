// knit/tiling.hpp — where pattern tiles go in UV space, and which tiles a mesh needs.
//
// Alignment convention (stable; tests depend on it): with repeats (U, V), pattern point (x, y)
// of tile (i, j) has uv = ((x + i*px) / (U*px), (y + j*py) / (V*py)). The pattern file's own
// origin goes to uv (0, 0); nothing is re-centred. Heights and radii are scaled by the same
// physical factor as the period (see PatternPlacement::scale).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "knit/base_mesh.hpp"
#include "knit/pattern.hpp"

namespace knit {

struct PatternPlacement {
    glm::dvec2 repeats{1.0};  // pattern periods across u in [0,1] and v in [0,1]
    // Metres of object space per metre of pattern space: applied to heights and radii.
    // sqrt(sx * sy) of the per-axis factors sx = metresPerU / (U * px), sy = metresPerV / (V * py).
    double scale = 1.0;
    // Metres one period spans on the mesh along u and v (metresPerU / U, metresPerV / V): with
    // the pattern's stitches and rows per period, the gauge achieved.
    glm::dvec2 periodMetres{0.0};
    glm::dvec2 cellSize() const { return {1.0 / repeats.x, 1.0 / repeats.y}; }
};

// A knitter's gauge: `stitches` stitch columns and `rows` rows measure `length` metres.
struct Gauge {
    double stitches = 0, rows = 0;
    double length = 0;  // metres
};
// Parses "STITCHES x ROWS / LENGTH" with LENGTH a number and a unit mm, cm, m or in, e.g.
// "22x30/10cm" (blanks allowed, X for x). Throws knit::Error "the gauge 'TEXT': what is wrong".
Gauge parseGauge(const std::string& text);

struct PlacementOptions {
    // (0, 0): keep the pattern's physical size on the mesh, using the mesh's own UV-to-metre
    // scale (uvToMetreScale); repeats then need not be integers.
    glm::dvec2 repeats{0.0};
    // Instead of repeats: the physical size of a stitch. One period is then
    // pattern.stitchesPerPeriod stitches by pattern.rowsPerPeriod rows of this gauge.
    std::optional<Gauge> gauge;
};
// Throws knit::Error for negative, NaN or absurd repeats, and for a gauge with repeats.
PatternPlacement placePattern(const Pattern& pattern, const BaseMesh& mesh, const PlacementOptions& options);

// A set of tiles (copies of the pattern cell) to generate, with O(1) lookup.
struct Tiling {
    std::vector<glm::ivec2> tiles;   // sorted row-major (by j, then i)
    glm::ivec2 minTile{0}, dims{0};  // bounding box of tiles
    std::vector<int32_t> tileSlot;   // dims.x*dims.y: -1 or index into tiles
    // Neighbours wrap around the bounding box (the tiling is a torus): for topology checks
    // and `knit info`, never for mapping.
    bool periodic = false;

    int32_t slotOf(glm::ivec2 t) const {
        glm::ivec2 r = t - minTile;
        if (periodic) {
            r.x = ((r.x % dims.x) + dims.x) % dims.x;
            r.y = ((r.y % dims.y) + dims.y) % dims.y;
        } else if (r.x < 0 || r.y < 0 || r.x >= dims.x || r.y >= dims.y) {
            return -1;
        }
        return tileSlot[size_t(r.y) * size_t(dims.x) + size_t(r.x)];
    }
};

// Tiles whose vertices can land in any of the given UV cells (cells of size placement.cellSize(),
// e.g. UvGrid::cells). The pattern's vertices may lie outside [0, px) x [0, py), so a tile can
// reach into neighbouring cells; this dilates accordingly. Only cells the mesh covers are tiled.
// `margin` (pattern units, per axis; addition, default 0): a vertex also counts for the cells
// within this distance of it, so a vertex just outside the covered cells (within binding's clamp
// tolerance of the UV boundary) is generated and clamped instead of silently missing.
Tiling tilesForCells(const Pattern& pattern, const std::vector<glm::ivec2>& cells, glm::dvec2 margin = glm::dvec2(0.0));
// The cells (relative to its own tile) that a tile's vertices, grown by `margin`, fall into:
// tile t reaches cells t + [lo, hi]. tilesForCells marks (cell span + hi - lo) tiles; a pattern
// vertex far outside its cell makes that large, so the pipeline sizes it first (knit/budget.hpp).
struct TileReach {
    glm::ivec2 lo{0}, hi{0};
};
TileReach tileReach(const Pattern& pattern, glm::dvec2 margin = glm::dvec2(0.0));
// All tiles in [first, last] (inclusive): per-region generation for level of detail.
// periodic: the region wraps around (a torus of (last - first + 1) tiles).
Tiling tilesForRegion(glm::ivec2 first, glm::ivec2 last, bool periodic = false);

}  // namespace knit
