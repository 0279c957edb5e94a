// classifyCells: frustum and back-face culling per UV cell, then the level by projected size with
// hysteresis (knit/detail.hpp).
#include <limits>
#include <algorithm>
#include <map>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/detail.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"

namespace knit {
namespace {

// True when every edge of the mesh (3D topology) is shared by exactly two triangles.
bool meshIsClosed(const BaseMesh& mesh) {
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (const glm::uvec3& f : mesh.faces)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = f[e], b = f[(e + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    if (uses.empty()) return false;
    return std::all_of(uses.begin(), uses.end(), [](const auto& u) { return u.second == 2; });
}

// Step (frustum): every corner of the cell's triangles lies farther than `grow` outside one plane.
bool outsideFrustum(const BaseMesh& mesh, const uint32_t* tris, size_t count, const std::array<Plane, 5>& planes,
                    double grow) {
    for (const Plane& plane : planes) {
        bool allOutside = true;
        for (size_t i = 0; i < count && allOutside; ++i)
            for (int c = 0; c < 3 && allOutside; ++c)
                allOutside = plane.distance(mesh.positions[mesh.faces[tris[i]][c]]) < -grow;
        if (allOutside) return true;
    }
    return false;
}

// Step (back faces): every triangle faces away from the eye even with its corners moved by
// `grow` along its normal (yarns above or below the surface).
bool facesAway(const BaseMesh& mesh, const uint32_t* tris, size_t count, const View& view, const ViewBasis& basis,
               double grow) {
    for (size_t i = 0; i < count; ++i) {
        const glm::uvec3 f = mesh.faces[tris[i]];
        const glm::dvec3 a = mesh.positions[f.x], b = mesh.positions[f.y], c = mesh.positions[f.z];
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        if (!(len > 0)) return false;  // a degenerate triangle has no side: keep the cell
        const glm::dvec3 u = n / len;
        for (const glm::dvec3& p : {a, b, c}) {
            // Orthographic: the eye is at infinity behind the image, so only the direction counts.
            const bool away = view.orthographic ? glm::dot(u, basis.forward) > 0 : glm::dot(u, view.eye - p) < -grow;
            if (!away) return false;
        }
    }
    return true;
}

// Step (nearest depth): the smallest depth of the cell's corners minus the margin, at least a
// millionth of the margin (a cell reaching behind the eye is as close as it gets). The floor is
// relative: a fixed micrometre made every cell of a 1e-12 m scene look a million times too far,
// so it was drawn as its surface level (an empty image, without a word).
double nearestDepth(const BaseMesh& mesh, const uint32_t* tris, size_t count, const View& view, const ViewBasis& basis,
                    double grow) {
    double depth = 1e300;
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c)
            depth = std::min(depth, glm::dot(mesh.positions[mesh.faces[tris[i]][c]] - view.eye, basis.forward));
    return std::max(depth - grow, grow > 0 ? 1e-6 * grow : std::numeric_limits<double>::min());
}

// Step (level): plies, yarns or surface by projected radius, keeping the previous level while
// its leave threshold holds.
DetailLevel levelOf(double plyPx, double yarnPx, DetailLevel previous, const DetailOptions& o) {
    if (plyPx >= o.plyPixels.enter || (previous == DetailLevel::Plies && plyPx >= o.plyPixels.leave))
        return DetailLevel::Plies;
    const bool wasYarnsOrMore = previous == DetailLevel::Plies || previous == DetailLevel::Yarns;
    if (yarnPx >= o.yarnPixels.enter || (wasYarnsOrMore && yarnPx >= o.yarnPixels.leave))
        return o.yarnLevel ? DetailLevel::Yarns : DetailLevel::Plies;
    return DetailLevel::Surface;
}

struct IvecHash {
    size_t operator()(const glm::ivec2& c) const { return std::hash<int64_t>()((int64_t(c.x) << 32) ^ uint32_t(c.y)); }
};

// The previous level of every cell of the grid (Culled where it had none).
std::vector<DetailLevel> previousLevels(const UvGrid& grid, const CellLevels* previous) {
    std::vector<DetailLevel> out(grid.cells.size(), DetailLevel::Culled);
    if (previous == nullptr) return out;
    if (previous->cells.size() != previous->level.size())
        throw Error("cannot build the view: the previous levels have " + std::to_string(previous->level.size()) +
                    " levels for " + std::to_string(previous->cells.size()) + " cells");
    std::unordered_map<glm::ivec2, DetailLevel, IvecHash> byCell;
    for (size_t k = 0; k < previous->cells.size(); ++k) byCell[previous->cells[k]] = previous->level[k];
    for (size_t k = 0; k < grid.cells.size(); ++k) {
        const auto it = byCell.find(grid.cells[k]);
        if (it != byCell.end()) out[k] = it->second;
    }
    return out;
}

}  // namespace

const char* detailLevelName(DetailLevel level) {
    switch (level) {
        case DetailLevel::Culled: return "culled";
        case DetailLevel::Surface: return "surface";
        case DetailLevel::Yarns: return "yarns";
        case DetailLevel::Plies: return "plies";
    }
    return "?";
}

double yarnMargin(const Binding& binding, double yarnRadius) {
    double h = 0;
    for (double v : binding.height) h = std::max(h, std::abs(v));
    return h + yarnRadius;
}

double yarnMargin(const Pattern& pattern, double scale, double yarnRadius) {
    double h = 0;
    for (const glm::dvec3& q : pattern.points) h = std::max(h, std::abs(q.z * scale));
    return h + yarnRadius;
}

CellLevels classifyCells(const DetailInputs& in, const View& view, const DetailOptions& o) {
    validateView(view);
    if (in.mesh == nullptr || in.grid == nullptr) throw Error("cannot build the view: no mesh or grid to classify");
    if (!util::positiveFinite(in.yarnRadius) || !util::positiveFinite(in.plyRadius) || !(in.margin >= 0))
        throw Error("cannot build the view: the yarn and ply radii must be positive and the margin not negative");
    if (!(o.shadowMargin >= 0) || !(o.plyPixels.leave <= o.plyPixels.enter) ||
        !(o.yarnPixels.leave <= o.yarnPixels.enter))
        throw Error(
            "cannot build the view: the shadow margin must be >= 0 and each leave threshold <= its enter threshold");
    const BaseMesh& mesh = *in.mesh;
    const UvGrid& grid = *in.grid;
    const std::array<Plane, 5> planes = frustumPlanes(view);
    const ViewBasis basis = viewBasis(view);
    const bool cullBack = o.cullBackFaces && !o.backLit && meshIsClosed(mesh);
    const double frustumGrow = in.margin + o.shadowMargin * in.yarnRadius;
    const std::vector<DetailLevel> before = previousLevels(grid, o.previous);
    CellLevels out;
    out.cells = grid.cells;
    out.level.assign(grid.cells.size(), DetailLevel::Culled);
    out.plyPixels.assign(grid.cells.size(), 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, grid.cells.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const uint32_t* tris = grid.triangles.data() + grid.triOffsets[k];
            const size_t count = grid.triOffsets[k + 1] - grid.triOffsets[k];
            if (count == 0 || outsideFrustum(mesh, tris, count, planes, frustumGrow)) continue;
            if (cullBack && facesAway(mesh, tris, count, view, basis, in.margin)) continue;
            const double px = pixelFootprint(view, nearestDepth(mesh, tris, count, view, basis, in.margin));
            out.plyPixels[k] = in.plyRadius / px;
            out.level[k] = levelOf(in.plyRadius / px, in.yarnRadius / px, before[k], o);
        }
    });
    return out;
}

}  // namespace knit
