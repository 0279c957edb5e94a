// The pipeline's size estimates (see scene_budget.hpp).
#include "scene_budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/geometric.hpp>

#include "knit/uv_grid.hpp"

namespace knit::impl {
namespace {

std::string count(double n, const char* what) {
    std::ostringstream s;
    s.precision(3);
    s << n << ' ' << what;
    return s.str();
}

const char* repeatsOption(bool physicalSize) {
    return physicalSize ? "the mesh's size at the pattern's physical size, or set the repeats," : "the repeats";
}

}  // namespace

void checkGridBudget(const BaseMesh& mesh, const PatternPlacement& placement, bool physicalSize,
                     const MemoryBudget& budget) {
    if (mesh.faceUvs.empty()) return;
    // The UVs the faces use (unreferenced UVs are never gridded).
    glm::dvec2 lo = mesh.uvs[mesh.faceUvs[0].x], hi = lo;
    for (const glm::uvec3& t : mesh.faceUvs)
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, mesh.uvs[t[k]]);
            hi = glm::max(hi, mesh.uvs[t[k]]);
        }
    // Cells touched by the UV box (+1 per axis for a box not aligned with the cells).
    const glm::dvec2 span = (hi - lo) * placement.repeats + 1.0;
    const double cells = std::floor(span.x + 1) * std::floor(span.y + 1);
    budget.require(cells * kBytesPerCell, count(cells, "pattern cells of the UV grid"), repeatsOption(physicalSize));
    // Each triangle is listed in every cell it touches: many more entries than cells when the
    // triangles are far larger than a cell or stacked on each other.
    const double entries = double(uvGridEntryBound(mesh, placement.cellSize()));
    budget.require(entries * kBytesPerGridEntry, count(entries, "triangle-cell entries of the UV grid"),
                   repeatsOption(physicalSize));
}

void checkTilingBudget(const Pattern& pattern, size_t coveredCells, glm::ivec2 cellSpan, const TileReach& reach,
                       bool physicalSize, const MemoryBudget& budget, bool regionOnly) {
    const glm::dvec2 reachSize = glm::dvec2(reach.hi) - glm::dvec2(reach.lo) + 1.0;
    // tilesForCells' marks over the cells' box grown by the reach, and the tiles it marks.
    const double marks = (double(cellSpan.x) + reachSize.x) * (double(cellSpan.y) + reachSize.y);
    const double tiles = std::min(marks, double(coveredCells) * reachSize.x * reachSize.y);
    const bool farVertex = reachSize.x * reachSize.y > 9;
    const std::string option =
        farVertex ? std::string("the pattern's vertices far outside its cell (in ") + pattern.name + ")"
                  : repeatsOption(physicalSize);
    budget.require(marks * 4 + tiles * 8, count(tiles, "pattern tiles"), option);
    const double vertices = tiles * double(pattern.points.size());
    budget.require(vertices * (regionOnly ? kBytesPerWalkedVertex : kBytesPerYarnVertex),
                   count(vertices, regionOnly ? "tiled yarn vertices to walk" : "yarn vertices"), option);
}

void checkRegionYarnBudget(uint64_t vertices, bool physicalSize, const MemoryBudget& budget) {
    budget.require(double(vertices) * kBytesPerYarnVertex, count(double(vertices), "yarn vertices through the view"),
                   std::string(repeatsOption(physicalSize)) + " (or move the camera back)");
}

void checkPlyBudget(const MappedYarns& yarns, const PlyOptions& resolved, const MemoryBudget& budget) {
    const Polylines& c = yarns.curves;
    double length = 0;
    for (size_t y = 0; y < c.curveCount(); ++y) {
        for (uint32_t i = c.begin(y) + 1; i < c.end(y); ++i) length += glm::distance(c.points[i - 1], c.points[i]);
        if (c.isClosed(y) && c.size(y) > 1) length += glm::distance(c.points[c.end(y) - 1], c.points[c.begin(y)]);
    }
    // One sample per yarn vertex at least, then samplesPerTurn per pitch along each yarn.
    checkPlyBudget(length / resolved.pitch * resolved.samplesPerTurn + double(c.pointCount()), resolved, budget);
}

void checkPlyBudget(double samples, const PlyOptions& resolved, const MemoryBudget& budget) {
    const double points = samples * resolved.count;
    budget.require(points * kBytesPerPlyPoint + samples * 96, count(points, "ply vertices"),
                   "the samples per turn, or raise the ply pitch,");
}

}  // namespace knit::impl
