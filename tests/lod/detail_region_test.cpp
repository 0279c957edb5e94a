// The region build of a view (buildScene with DetailOptions::region): only the yarns through the
// view's ply- and yarn-level cells are built, each the full scene's yarn vertex for vertex, so the
// pieces and plies are the full scene's bit for bit; a moving camera changes the kept set without
// cracks; the memory estimates made before allocating cover what the region build holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "knit/detail.hpp"
#include "knit/error.hpp"
#include "knit/plies.hpp"
#include "knit/scene.hpp"
#include "scene/scene_budget.hpp"

namespace knit {
namespace {

using Key = std::array<double, 3>;
Key key(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

// The drape at 16 x 16 quads, 60 x 60 repeats.
SceneOptions drapeOptions() {
    SceneOptions so;
    so.mesh = "drape";
    so.meshOptions.resU = so.meshOptions.resV = 16;
    so.placement.repeats = {60, 60};
    return so;
}

// A close camera `distance` metres along the normal of the drape's middle vertex, looking at it
// slightly obliquely; 64 x 48 pixels.
View closeView(const Scene& mesh, double distance, double slide = 0) {
    const BaseMesh& m = mesh.mesh();
    const size_t mid = m.positions.size() / 2;
    View v;
    v.target = m.positions[mid] + glm::dvec3(slide, 0, 0);
    v.eye = v.target + distance * glm::normalize(mesh.normals()[mid] + glm::dvec3(0.3, 0, 0));
    v.up = std::abs(mesh.normals()[mid].y) > 0.9 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
    v.width = 64, v.height = 48;
    return v;
}

Scene viewScene(const View& view, bool region, const CellLevels* previous = nullptr,
                const MemoryBudget* budget = nullptr) {
    SceneOptions so = drapeOptions();
    DetailOptions d;
    d.view = view;
    d.region = region;
    d.previous = previous;
    so.detail = d;
    if (budget) so.budget = *budget;
    return buildScene(so);
}

size_t keptCells(const CellLevels& l) {
    return size_t(std::count_if(l.level.begin(), l.level.end(),
                                [](DetailLevel x) { return x == DetailLevel::Plies || x == DetailLevel::Yarns; }));
}

// The full scene (no view), built once.
const Scene& fullScene() {
    static const Scene full = [] {
        SceneOptions so = drapeOptions();
        return buildScene(so);
    }();
    return full;
}

TEST(DetailRegion, regionBuildIsTheFullScenesPliesBitForBit) {
    const Scene& full = fullScene();
    const View view = closeView(full, 0.05);
    const Scene region = viewScene(view, true);
    const Scene whole = viewScene(view, false);  // the same view with every yarn built
    const SceneDetail& d = *region.detail();
    const size_t kept = keptCells(d.levels);
    ASSERT_GT(kept, 4u);
    ASSERT_LT(kept, d.levels.cells.size() / 4) << "the test needs a view that keeps a small part of the mesh";
    // Fewer yarns, and each is a full scene yarn vertex for vertex.
    EXPECT_EQ(whole.yarns().curves.pointCount(), full.yarns().curves.pointCount());
    EXPECT_LT(region.yarns().curves.pointCount() * 3, full.yarns().curves.pointCount());
    std::map<Key, size_t> fullYarnAt;  // first vertex -> full yarn
    const Polylines& fy = full.yarns().curves;
    for (size_t y = 0; y < fy.curveCount(); ++y) fullYarnAt[key(fy.points[fy.begin(y)])] = y;
    const Polylines& ry = region.yarns().curves;
    std::vector<size_t> fullOf(ry.curveCount());
    for (size_t y = 0; y < ry.curveCount(); ++y) {
        const auto it = fullYarnAt.find(key(ry.points[ry.begin(y)]));
        ASSERT_NE(it, fullYarnAt.end()) << "region yarn " << y << " starts where no full yarn starts";
        fullOf[y] = it->second;
        ASSERT_EQ(fy.size(it->second), ry.size(y));
        EXPECT_TRUE(std::equal(ry.points.begin() + ry.begin(y), ry.points.begin() + ry.end(y),
                               fy.points.begin() + fy.begin(it->second)))
            << "region yarn " << y;
        EXPECT_EQ(ry.isClosed(y), fy.isClosed(it->second));
    }
    // The pieces and the plies inside the region are those of the view built with every yarn, bit
    // for bit (and those are the full scene's: Detail.plyLevelPliesAreTheFullScenesPliesPointForPoint).
    const LevelPieces& a = d.pieces;
    const LevelPieces& b = whole.detail()->pieces;
    EXPECT_EQ(a.plies.curves.points, b.plies.curves.points);
    EXPECT_EQ(a.plies.curves.offsets, b.plies.curves.offsets);
    EXPECT_EQ(a.yarns.curves.points, b.yarns.curves.points);
    EXPECT_EQ(a.surfaceFaces, b.surfaceFaces);
    ASSERT_GT(region.plies().curves.pointCount(), 0u);
    EXPECT_EQ(region.plies().curves.points, whole.plies().curves.points);
    EXPECT_EQ(region.plies().radial, whole.plies().radial);
    EXPECT_EQ(region.plies().curves.offsets, whole.plies().curves.offsets);
    // And directly: every ply curve of the region is a run of the same ply of the full scene's
    // plies of the same yarn.
    const Plies fullPlies = makePlies(full.yarns(), full.plyOptions());
    std::map<std::pair<uint32_t, uint8_t>, size_t> wholeCurve;
    for (size_t c = 0; c < fullPlies.curves.curveCount(); ++c)
        wholeCurve[{fullPlies.yarnOfCurve[c], fullPlies.plyOfCurve[c]}] = c;
    const Polylines& rp = region.plies().curves;
    for (size_t c = 0; c < rp.curveCount(); ++c) {
        const size_t w = wholeCurve.at({uint32_t(fullOf[region.plies().yarnOfCurve[c]]), region.plies().plyOfCurve[c]});
        const Polylines& wp = fullPlies.curves;
        const auto first =
            std::find(wp.points.begin() + wp.begin(w), wp.points.begin() + wp.end(w), rp.points[rp.begin(c)]);
        ASSERT_NE(first, wp.points.begin() + wp.end(w)) << "ply curve " << c;
        const size_t off = size_t(first - (wp.points.begin() + wp.begin(w)));
        ASSERT_LE(off + rp.size(c), wp.size(w)) << "ply curve " << c;
        EXPECT_TRUE(std::equal(rp.points.begin() + rp.begin(c), rp.points.begin() + rp.end(c), first))
            << "ply curve " << c << " is not a run of the full scene's ply";
    }
}

// A camera sliding and approaching along a path, each frame classified with the previous one's
// levels: the kept set changes, every frame's pieces are those of the view with every yarn (no
// gap at the region's edge), and the yarns through cells kept in two consecutive frames are the
// same there, bit for bit (no crack where the two kept sets meet).
TEST(DetailRegion, cameraPathChangesTheKeptSetWithoutCracks) {
    const Scene& full = fullScene();
    std::vector<View> path;
    for (int k = 0; k < 4; ++k) path.push_back(closeView(full, 0.06 - 0.008 * k, 0.02 * k));
    std::vector<Scene> frames;
    frames.reserve(path.size());  // each frame's levels are the next one's previous levels
    size_t entered = 0, left = 0;
    for (size_t k = 0; k < path.size(); ++k) {
        const CellLevels* previous = k > 0 ? &frames.back().detail()->levels : nullptr;
        frames.push_back(viewScene(path[k], true, previous));
        const Scene whole = viewScene(path[k], false, previous);
        const LevelPieces& a = frames.back().detail()->pieces;
        const LevelPieces& b = whole.detail()->pieces;
        EXPECT_EQ(a.plies.curves.points, b.plies.curves.points) << "frame " << k;
        EXPECT_EQ(a.yarns.curves.points, b.yarns.curves.points) << "frame " << k;
        EXPECT_EQ(frames.back().plies().curves.points, whole.plies().curves.points) << "frame " << k;
        if (k == 0) continue;
        const CellLevels& l0 = frames[k - 1].detail()->levels;
        const CellLevels& l1 = frames[k].detail()->levels;
        ASSERT_EQ(l0.cells, l1.cells);
        std::set<std::pair<int, int>> both;
        for (size_t c = 0; c < l0.level.size(); ++c) {
            const bool k0 = l0.level[c] >= DetailLevel::Yarns, k1 = l1.level[c] >= DetailLevel::Yarns;
            entered += !k0 && k1;
            left += k0 && !k1;
            if (k0 && k1) both.insert({l0.cells[c].x, l0.cells[c].y});
        }
        ASSERT_FALSE(both.empty()) << "frames " << k - 1 << " and " << k << " share no kept cell";
        // The yarn vertices bound in cells kept by both frames: the same set, bit for bit.
        auto sharedVertices = [&](const Scene& s) {
            std::set<Key> out;
            const Binding& bnd = s.binding();
            const BaseMesh& m = s.mesh();
            for (size_t i = 0; i < bnd.vertexCount(); ++i) {
                const glm::uvec3 f = m.faceUvs[bnd.face[i]];
                const glm::dvec2 b = bnd.bary[i];
                const glm::dvec2 uv = (1 - b.x - b.y) * m.uvs[f.x] + b.x * m.uvs[f.y] + b.y * m.uvs[f.z];
                const glm::ivec2 cell = s.grid().cellOf(uv);
                if (both.count({cell.x, cell.y})) out.insert(key(s.yarns().curves.points[i]));
            }
            return out;
        };
        const std::set<Key> before = sharedVertices(frames[k - 1]), after = sharedVertices(frames[k]);
        EXPECT_GT(before.size(), 100u);
        EXPECT_EQ(before, after) << "frames " << k - 1 << " and " << k;
    }
    EXPECT_GT(entered, 0u);
    EXPECT_GT(left, 0u);
}

// Bytes the region build holds per yarn vertex: UV yarns, binding, mapped yarns and normals.
double heldBytes(const Scene& s) {
    const UvYarns& u = s.stages().uvYarns;
    const Binding& b = s.binding();
    const MappedYarns& y = s.yarns();
    return double(u.uv.size() * 16 + u.height.size() * 8 + u.twist.size() * 8 + u.source.size() * 4 +
                  u.colour.size() * 12 + u.offsets.size() * 4 + b.face.size() * 4 + b.bary.size() * 16 +
                  b.height.size() * 8 + b.twist.size() * 8 + b.colour.size() * 12 + b.source.size() * 4 +
                  b.offsets.size() * 4 + y.curves.points.size() * 24 + y.normals.size() * 24 + y.colour.size() * 12);
}

TEST(DetailRegion, memoryEstimatesCoverTheRegionBuild) {
    const Scene& full = fullScene();
    const View view = closeView(full, 0.05);
    const Scene region = viewScene(view, true);
    const double vertices = double(region.stages().uvYarns.vertexCount());
    ASSERT_GT(vertices, 0);
    // The estimate checked before the region's yarns are allocated covers what they hold.
    EXPECT_GE(vertices * impl::kBytesPerYarnVertex, heldBytes(region));
    // A budget the full scene's yarns do not fit, but the region's do: the view builds, the full
    // scene (and the view with every yarn) is refused before tiling allocates its yarns.
    const double fullYarns = double(full.stages().uvYarns.vertexCount()) * impl::kBytesPerYarnVertex;
    const double regionYarns = vertices * impl::kBytesPerYarnVertex;
    ASSERT_LT(regionYarns * 3, fullYarns);
    const MemoryBudget between(uint64_t(fullYarns / 2));
    EXPECT_NO_THROW(viewScene(view, true, nullptr, &between));
    EXPECT_THROW(viewScene(view, false, nullptr, &between), Error);
    // Below the region's own yarns: refused, naming them, before they are allocated.
    const MemoryBudget tight(uint64_t(regionYarns * 0.9));
    try {
        viewScene(view, true, nullptr, &tight);
        ADD_FAILURE() << "a budget below the region's yarns was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("yarn vertices through the view"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace knit
