// knit/detail.hpp — level of detail per UV cell for a view: which cells are culled, which get
// plies, which keep only the yarn curve and which are left to the base-mesh surface; and the
// mapped yarns cut into pieces per level (crack-free: neighbouring pieces share their end point).
//
// The UV cell (tile i, j of UvGrid::cells) is the unit: cell identities do not depend on the view,
// so levels of one view can be passed to the next (hysteresis) and cached cells reused.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/uv_grid.hpp"
#include "knit/view.hpp"

namespace knit {

// Ordered from least to most geometry.
enum class DetailLevel : uint8_t { Culled, Surface, Yarns, Plies };
const char* detailLevelName(DetailLevel level);  // "culled" | "surface" | "yarns" | "plies"

// A level is entered when the projected radius reaches `enter` pixels and kept while it stays at
// or above `leave` (< enter): a camera that moves a little does not flip cells at the threshold.
struct Hysteresis {
    double enter = 1.0;
    double leave = 0.8;
};

// Per cell of the grid (same order as UvGrid::cells).
struct CellLevels {
    std::vector<glm::ivec2> cells;   // the cell ids (tile i, j)
    std::vector<DetailLevel> level;  // per cell
    std::vector<double> plyPixels;   // projected ply radius in pixels at the cell's nearest point
};

struct DetailOptions {
    std::optional<View> view;  // none: frameMesh(mesh, margin, viewSettings), the default camera
    View viewSettings;         // field of view and image size when framing
    // Back-lit renders see light through the cloth: back-facing cells are kept.
    bool backLit = false;
    // Cull cells whose every triangle faces away. Only where the mesh is closed: on an open mesh
    // the back of the cloth is what is seen from behind.
    bool cullBackFaces = true;
    // Frustum margin beyond the yarns' height and radius, in yarn radii (shadows cast into the view).
    double shadowMargin = 4.0;
    // Ply radius in pixels for the ply level, and yarn radius in pixels for the yarn level: plies
    // wherever a yarn is about a pixel wide or more (for two plies, a ply radius of a quarter
    // pixel is a yarn radius of half a pixel, so the two meet and such yarns go from plies
    // straight to the surface). Measured on the garment (docs/views.md): with plies only from a
    // ply radius of 1 pixel, the close-up's yarn-level half (plies 1-2 pixels wide, whose twist
    // and crevices a round curve cannot show) was 7.5% off in 4 x 4 blocks, where two full
    // renders differ by 4.2%; the grazing mid view's surface level, where yarns are 1-2 pixels
    // wide, 7.1% against 4.5%. With these defaults both are within the two full renders'
    // difference.
    Hysteresis plyPixels{0.25, 0.2};
    Hysteresis yarnPixels{0.5, 0.4};
    // false: cells of the yarn level get plies (for consumers that cannot draw yarn curves).
    bool yarnLevel = true;
    // buildScene: build only the yarns through the view's ply- and yarn-level cells (yarnRegion),
    // each whole, so their plies are the full scene's point for point; false: every yarn of the
    // mesh (Scene::yarns() then holds them all).
    bool region = true;
    // The levels of a previous view of the same grid (hysteresis); nullptr: none.
    const CellLevels* previous = nullptr;
};

// What the classification needs to know of the scene (all object-space metres).
struct DetailInputs {
    const BaseMesh* mesh = nullptr;
    const UvGrid* grid = nullptr;
    double margin = 0;  // the yarns' greatest height above or below the surface plus their radius
    double yarnRadius = 0;
    double plyRadius = 0;
};

// The margin of DetailInputs: max |height| of the binding plus the yarn radius.
double yarnMargin(const Binding& binding, double yarnRadius);
// The same from the pattern before any yarn exists: max |z| of its points times the placement's
// scale, plus the yarn radius. Equal to the binding's (bit for bit) when the pattern's highest or
// lowest point is bound somewhere, which any mesh wider than a tile has; never smaller.
double yarnMargin(const Pattern& pattern, double scale, double yarnRadius);

// Culls and picks a level for every cell of the grid (view validated: knit::Error naming the
// option). Culled: the cell's triangles, grown by margin + shadowMargin yarn radii, lie outside one
// frustum plane; or (cullBackFaces, not backLit, closed mesh) every triangle faces away from the eye.
CellLevels classifyCells(const DetailInputs& in, const View& view, const DetailOptions& options);

// The cells a view builds yarns for (buildScene with SceneOptions::detail): every cell at the ply
// or yarn level, grown by `ring` cells on each side (binding clamps a vertex just outside its
// cell onto it), row-major, each once. buildScene keeps the whole yarns that pass through them
// (stitched over every tile, so each is the full scene's yarn vertex for vertex) and drops the
// others before binding; their pieces and plies are then the full scene's.
std::vector<glm::ivec2> yarnRegion(const CellLevels& levels, int ring = 1);

// The mapped yarns cut per level: each run of vertices in cells of one level is a piece; where two
// runs meet, both pieces end at the same point, where the yarn leaves the cell of the last vertex
// of the first run (linear in the segment). Culled runs are dropped; a yarn all in one level is
// kept whole (closed loops stay closed).
// Where a piece lies on its source yarn: from `begin` to `end` in vertex units of the yarn
// (vertex k of the yarn is k; k + t is the fraction t of the way to vertex k + 1; on a closed yarn
// end may exceed the vertex count: the piece wraps past the first vertex); `loop`: the whole
// closed yarn.
struct YarnSpan {
    uint32_t yarn = 0;
    double begin = 0, end = 0;
    bool loop = false;
};

struct LevelPieces {
    MappedYarns plies;                                  // pieces of ply-level cells (plies are generated for these)
    MappedYarns yarns;                                  // pieces of yarn-level cells (drawn as yarn curves)
    std::vector<uint32_t> surfaceFaces;                 // base-mesh triangles touching a surface-level cell, ascending
    std::vector<uint32_t> plyPieceYarn, yarnPieceYarn;  // source yarn of each piece
    std::vector<YarnSpan> plySpans, yarnSpans;          // where each piece lies on its source yarn
};
LevelPieces splitByLevel(const MappedYarns& yarns, const Binding& binding, const BaseMesh& mesh, const UvGrid& grid,
                         const CellLevels& levels);

// The plies of pieces (src/detail_plies.cpp), cut from the plies of their whole source yarns, so
// they are the plies makePlies(yarns, options) makes, point for point (the twist phase and the
// frames run from the yarn's start, not the piece's). Each piece's plies reach one resampled
// point past each end of its span (neighbouring levels overlap; no gap); a `loop` span gives the
// yarn's closed plies. Pieces must be grouped by yarn in ascending order (as splitByLevel
// writes them). yarnOfCurve holds the source yarns; radial and colour as makePlies.
Plies piecePlies(const MappedYarns& yarns, const std::vector<YarnSpan>& spans, const PlyOptions& options);

}  // namespace knit
