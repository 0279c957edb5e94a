// Culling and levels of detail per UV cell (knit/detail.hpp): frustum and back-face culling
// against brute force, crack-free pieces across level boundaries, stable levels under a small
// camera move.
#include <gtest/gtest.h>

#include <algorithm>

#include <map>
#include <random>
#include <tuple>

#include "common/fixtures.hpp"
#include "common/ply_runs.hpp"
#include "knit/detail.hpp"
#include "knit/plies.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

struct Cells {
    BaseMesh mesh;
    UvGrid grid;
};

Cells gridOf(BaseMesh mesh, double cell) {
    Cells c{std::move(mesh), {}};
    UvGridOptions o;
    o.cellSize = glm::dvec2(cell);
    c.grid = buildUvGrid(c.mesh, o);
    return c;
}

DetailInputs inputsOf(const Cells& c, double yarnRadius, double plyRadius) {
    DetailInputs in;
    in.mesh = &c.mesh, in.grid = &c.grid, in.margin = 0, in.yarnRadius = yarnRadius, in.plyRadius = plyRadius;
    return in;
}

// Points spread over the triangles of cell k (corners and random interior points).
std::vector<glm::dvec3> cellSamples(const Cells& c, size_t k) {
    std::mt19937 rng{static_cast<uint32_t>(k)};
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<glm::dvec3> pts;
    for (uint32_t i = c.grid.triOffsets[k]; i < c.grid.triOffsets[k + 1]; ++i) {
        const glm::uvec3 f = c.mesh.faces[c.grid.triangles[i]];
        const glm::dvec3 a = c.mesh.positions[f.x], b = c.mesh.positions[f.y], d = c.mesh.positions[f.z];
        pts.insert(pts.end(), {a, b, d});
        for (int s = 0; s < 40; ++s) {
            double x = u(rng), y = u(rng);
            if (x + y > 1) x = 1 - x, y = 1 - y;
            pts.push_back(a + x * (b - a) + y * (d - a));
        }
    }
    return pts;
}

bool seen(const View& v, const glm::dvec3& p) {
    const glm::dvec3 px = projectToPixel(v, p);
    return px.z > 0 && px.x >= 0 && px.x <= v.width && px.y >= 0 && px.y <= v.height;
}

TEST(Detail, frustumCullingMatchesBruteForcePerCell) {
    const Cells c = gridOf(test::planeMesh(test::Triangulation::Random, 12, 1.0), 1.0 / 24);
    View v;
    v.eye = {0.2, 0.3, 0.4}, v.target = {0.35, 0.2, 0.0}, v.up = {0, 1, 0}, v.fovDegrees = 40;
    v.width = 64, v.height = 48;
    DetailOptions o;
    o.shadowMargin = 0;
    const CellLevels levels = classifyCells(inputsOf(c, 1e-3, 5e-4), v, o);
    size_t culled = 0, visible = 0;
    for (size_t k = 0; k < c.grid.cells.size(); ++k) {
        bool anySeen = false;
        for (const glm::dvec3& p : cellSamples(c, k)) anySeen = anySeen || seen(v, p);
        if (anySeen) EXPECT_NE(levels.level[k], DetailLevel::Culled) << k;  // never cull what is seen
        // Brute force of the rule: all corners outside one plane <=> culled (margin 0).
        bool outside = false;
        for (const Plane& pl : frustumPlanes(v)) {
            bool all = true;
            for (uint32_t i = c.grid.triOffsets[k]; i < c.grid.triOffsets[k + 1]; ++i)
                for (int j = 0; j < 3; ++j)
                    all = all && pl.distance(c.mesh.positions[c.mesh.faces[c.grid.triangles[i]][j]]) < 0;
            outside = outside || all;
        }
        EXPECT_EQ(outside, levels.level[k] == DetailLevel::Culled) << k;
        (levels.level[k] == DetailLevel::Culled ? culled : visible) += 1;
    }
    EXPECT_GT(culled, c.grid.cells.size() / 2);
    EXPECT_GT(visible, 10u);
}

TEST(Detail, frustumMarginKeepsCellsJustOutsideTheImage) {
    const Cells c = gridOf(test::planeMesh(test::Triangulation::Regular, 8, 1.0), 1.0 / 16);
    View v;
    v.eye = {0.5, 0.5, 0.5}, v.target = {0.5, 0.5, 0.0}, v.fovDegrees = 30, v.width = v.height = 32;
    DetailOptions o;
    o.shadowMargin = 0;
    DetailInputs in = inputsOf(c, 1e-3, 5e-4);
    const CellLevels tight = classifyCells(in, v, o);
    in.margin = 0.2;  // beyond the next ring of triangles (0.125 wide)
    const CellLevels grown = classifyCells(in, v, o);
    size_t tightKept = 0, grownKept = 0;
    for (size_t k = 0; k < tight.level.size(); ++k) {
        tightKept += tight.level[k] != DetailLevel::Culled;
        grownKept += grown.level[k] != DetailLevel::Culled;
        if (tight.level[k] != DetailLevel::Culled) EXPECT_NE(grown.level[k], DetailLevel::Culled);
    }
    EXPECT_GT(grownKept, tightKept);
}

// Back faces: on a closed sphere seen from outside, culled cells have only triangles facing away
// (brute force per triangle corner); an open plane seen from behind and back-lit renders keep all.
TEST(Detail, backFacesCulledOnlyOnClosedMeshesAndNotWhenBackLit) {
    ProceduralMeshOptions po;
    po.radius = 0.1, po.resU = 24, po.resV = 12;
    const Cells sphere = gridOf(makeSphere(po), 1.0 / 16);
    View v;
    v.eye = {0, 0, 1.0}, v.target = {0, 0, 0}, v.fovDegrees = 30, v.width = v.height = 64;
    DetailOptions o;
    o.shadowMargin = 0;
    const CellLevels levels = classifyCells(inputsOf(sphere, 1e-3, 5e-4), v, o);
    size_t culled = 0;
    for (size_t k = 0; k < sphere.grid.cells.size(); ++k) {
        bool anyFront = false;
        for (uint32_t i = sphere.grid.triOffsets[k]; i < sphere.grid.triOffsets[k + 1]; ++i) {
            const glm::uvec3 f = sphere.mesh.faces[sphere.grid.triangles[i]];
            const glm::dvec3 a = sphere.mesh.positions[f.x], b = sphere.mesh.positions[f.y],
                             d = sphere.mesh.positions[f.z];
            const glm::dvec3 n = glm::cross(b - a, d - a);
            for (const glm::dvec3& p : {a, b, d}) anyFront = anyFront || glm::dot(n, v.eye - p) >= 0;
        }
        if (anyFront) EXPECT_NE(levels.level[k], DetailLevel::Culled) << k;
        else EXPECT_EQ(levels.level[k], DetailLevel::Culled) << k;
        culled += levels.level[k] == DetailLevel::Culled;
    }
    EXPECT_GT(culled, sphere.grid.cells.size() / 3);
    o.backLit = true;
    for (DetailLevel l : classifyCells(inputsOf(sphere, 1e-3, 5e-4), v, o).level) EXPECT_NE(l, DetailLevel::Culled);
    // An open plane (z = 0, front +z) seen from behind: its back is what is seen, nothing is culled.
    const Cells plane = gridOf(test::planeMesh(test::Triangulation::Regular, 4, 0.2), 1.0 / 8);
    v.eye = {0.1, 0.1, -1.0}, v.target = {0.1, 0.1, 0};
    o.backLit = false;
    for (DetailLevel l : classifyCells(inputsOf(plane, 1e-3, 5e-4), v, o).level) EXPECT_NE(l, DetailLevel::Culled);
}

View grazingView() {
    View v;
    v.eye = {0.5, -0.6, 0.35}, v.target = {0.5, 0.6, 0.0}, v.up = {0, 0, 1}, v.fovDegrees = 60;
    v.width = 300, v.height = 400;
    return v;
}

// Both levels entered at 1 pixel, left at 0.8 (the defaults enter the ply level at 0.5).
DetailOptions onePixel() {
    DetailOptions o;
    o.plyPixels = {1.0, 0.8};
    o.yarnPixels = {1.0, 0.8};
    return o;
}

TEST(Detail, levelsFollowProjectedSize) {
    const Cells c = gridOf(test::planeMesh(test::Triangulation::Regular, 16, 1.0), 1.0 / 32);
    const CellLevels levels = classifyCells(inputsOf(c, 3e-3, 2e-3), grazingView(), onePixel());
    std::map<DetailLevel, size_t> count;
    for (size_t k = 0; k < levels.level.size(); ++k) {
        ++count[levels.level[k]];
        const double ply = levels.plyPixels[k], yarn = ply * 1.5;
        if (levels.level[k] == DetailLevel::Plies) EXPECT_GE(ply, 1.0);
        if (levels.level[k] == DetailLevel::Yarns) EXPECT_TRUE(ply < 1.0 && yarn >= 1.0);
        if (levels.level[k] == DetailLevel::Surface) EXPECT_LT(yarn, 1.0);
    }
    EXPECT_GT(count[DetailLevel::Plies], 0u);
    EXPECT_GT(count[DetailLevel::Yarns], 0u);
    EXPECT_GT(count[DetailLevel::Surface], 0u);
}

TEST(Detail, onePercentCameraMoveChangesOnlyCellsNearThresholdsAndDoesNotFlicker) {
    const Cells c = gridOf(test::planeMesh(test::Triangulation::Regular, 16, 1.0), 1.0 / 32);
    const DetailInputs in = inputsOf(c, 3e-3, 2e-3);
    const View v0 = grazingView();
    View v1 = v0;
    v1.eye += 0.01 * glm::distance(v0.eye, v0.target) * glm::normalize(v0.target - v0.eye);  // 1% closer
    const CellLevels l0 = classifyCells(in, v0, onePixel());
    DetailOptions o = onePixel();
    o.previous = &l0;
    const CellLevels l1 = classifyCells(in, v1, o);
    size_t changed = 0;
    for (size_t k = 0; k < l0.level.size(); ++k) {
        if (l0.level[k] == l1.level[k]) continue;
        ++changed;
        // Only cells whose ply or yarn radius was within 2% of an enter threshold (1 px) move up.
        const double ply = l0.plyPixels[k], yarn = 1.5 * ply;
        EXPECT_TRUE(std::abs(ply - 1.0) < 0.02 || std::abs(yarn - 1.0) < 0.02) << ply;
        EXPECT_GT(l1.level[k], l0.level[k]);  // closer: only finer
    }
    EXPECT_LT(changed, l0.level.size() / 20);
    // Moving back keeps the finer levels (hysteresis): no flicker.
    o.previous = &l1;
    EXPECT_EQ(classifyCells(in, v0, o).level, l1.level);
    // Without a band the same move back flips them again.
    o.plyPixels.leave = o.plyPixels.enter, o.yarnPixels.leave = o.yarnPixels.enter;
    if (changed > 0) EXPECT_EQ(classifyCells(in, v0, o).level, l0.level);
}

// A plane scene whose cells alternate between the ply and the yarn level (and surface / culled
// when asked): every yarn that crosses levels stays one curve, cut at shared points.
struct PieceCase {
    Scene scene;
    CellLevels levels;
};

PieceCase alternatingLevels(bool withDropped, const char* mesh = "plane") {
    SceneOptions so;
    so.mesh = mesh;
    so.placement.repeats = {6, 6};
    so.buildPlies = false;
    PieceCase pc{buildScene(so), {}};
    const UvGrid& g = pc.scene.grid();
    pc.levels.cells = g.cells;
    for (const glm::ivec2& cell : g.cells) {
        const int m = ((cell.x + 2 * cell.y) % 4 + 4) % 4;
        DetailLevel l = m % 2 == 0 ? DetailLevel::Plies : DetailLevel::Yarns;
        if (withDropped && m == 3) l = DetailLevel::Surface;
        pc.levels.level.push_back(l);
    }
    pc.levels.plyPixels.assign(g.cells.size(), 0.0);
    return pc;
}

double length(const Polylines& p, size_t c) {
    double l = 0;
    for (uint32_t s = 0; s < p.segmentCount(c); ++s)
        l += glm::distance(p.points[p.begin(c) + s], p.points[p.begin(c) + (s + 1) % p.size(c)]);
    return l;
}

TEST(Detail, yarnAcrossLevelBoundaryHasNoGapAndNoDouble) {
    const PieceCase pc = alternatingLevels(false);
    const Scene& s = pc.scene;
    const LevelPieces pieces = splitByLevel(s.yarns(), s.binding(), s.mesh(), s.grid(), pc.levels);
    ASSERT_GT(pieces.plies.curves.curveCount(), 0u);
    ASSERT_GT(pieces.yarns.curves.curveCount(), 0u);
    // Lengths: the pieces of a yarn add up to the yarn (no gap, no overlap).
    std::vector<double> sum(s.yarns().curves.curveCount(), 0.0);
    for (size_t c = 0; c < pieces.plies.curves.curveCount(); ++c)
        sum[pieces.plyPieceYarn[c]] += length(pieces.plies.curves, c);
    for (size_t c = 0; c < pieces.yarns.curves.curveCount(); ++c)
        sum[pieces.yarnPieceYarn[c]] += length(pieces.yarns.curves, c);
    for (size_t y = 0; y < sum.size(); ++y) EXPECT_NEAR(sum[y], length(s.yarns().curves, y), 1e-12) << y;
    // End points: every cut point is the end of exactly one piece of each level (bit-identical).
    std::map<std::tuple<double, double, double>, std::pair<int, int>> ends;  // point -> (ply, yarn) ends
    auto count = [&](const Polylines& p, bool ply) {
        for (size_t c = 0; c < p.curveCount(); ++c)
            for (uint32_t i : {p.begin(c), p.end(c) - 1}) {
                const glm::dvec3 q = p.points[i];
                auto& e = ends[{q.x, q.y, q.z}];
                (ply ? e.first : e.second) += 1;
            }
    };
    count(pieces.plies.curves, true);
    count(pieces.yarns.curves, false);
    size_t cuts = 0;
    for (const auto& [point, e] : ends) {
        EXPECT_LE(e.first, 2);
        EXPECT_LE(e.second, 2);
        if (e.first > 0 && e.second > 0) {
            EXPECT_EQ(e.first, e.second);
            ++cuts;
        }
    }
    EXPECT_GT(cuts, 10u);
}

TEST(Detail, droppedLevelsLeaveNoYarnAndSurfaceCellsListTheirTriangles) {
    const PieceCase pc = alternatingLevels(true);
    const Scene& s = pc.scene;
    const LevelPieces pieces = splitByLevel(s.yarns(), s.binding(), s.mesh(), s.grid(), pc.levels);
    double kept = 0, all = 0;
    for (size_t c = 0; c < pieces.plies.curves.curveCount(); ++c) kept += length(pieces.plies.curves, c);
    for (size_t c = 0; c < pieces.yarns.curves.curveCount(); ++c) kept += length(pieces.yarns.curves, c);
    for (size_t y = 0; y < s.yarns().curves.curveCount(); ++y) all += length(s.yarns().curves, y);
    EXPECT_LT(kept, 0.9 * all);  // a quarter of the cells are surface: their yarn is gone
    EXPECT_GT(kept, 0.6 * all);
    EXPECT_FALSE(pieces.surfaceFaces.empty());
    for (size_t k = 0; k < s.grid().cells.size(); ++k)
        if (pc.levels.level[k] == DetailLevel::Surface)
            for (uint32_t i = s.grid().triOffsets[k]; i < s.grid().triOffsets[k + 1]; ++i)
                EXPECT_TRUE(
                    std::binary_search(pieces.surfaceFaces.begin(), pieces.surfaceFaces.end(), s.grid().triangles[i]));
}

TEST(Detail, sceneWithViewGeneratesPliesOnlyForPlyCells) {
    SceneOptions so;
    so.mesh = "plane";
    so.placement.repeats = {8, 8};
    const Scene full = buildScene(so);
    DetailOptions d;
    View v = frameMesh(full.mesh(), 0.01, View{});
    v.eye = v.target + 0.3 * (v.eye - v.target);  // closer: the image shows part of the cloth
    v.height = 60, v.width = 80;
    d.view = v;
    so.detail = d;
    const Scene near = buildScene(so);
    ASSERT_TRUE(near.detail().has_value());
    const SceneStats st = sceneStats(near);
    EXPECT_GT(st.levels.culledCells, 0u);
    EXPECT_EQ(st.levels.plies.plyVertices, near.plies().curves.pointCount());
    EXPECT_LT(near.plies().curves.pointCount(), full.plies().curves.pointCount());
    EXPECT_EQ(st.levels.plies.cells + st.levels.yarns.cells + st.levels.surface.cells + st.levels.culledCells,
              near.grid().cells.size());
    EXPECT_EQ(near.yarns().curves.pointCount(), full.yarns().curves.pointCount());  // all yarns kept
}

// A view in which every cell is culled or at the surface level (a far view) needs no yarn: the
// scene skips tiling, stitching, binding and evaluation, and still frames, classifies and lists
// the surface triangles exactly as when it built every yarn.
TEST(Detail, viewThatNeedsNoYarnsBuildsNone) {
    SceneOptions so;
    so.mesh = "drape";
    so.meshOptions.resU = so.meshOptions.resV = 16;
    so.placement.repeats = {60, 60};
    DetailOptions d;
    d.viewSettings.width = 32, d.viewSettings.height = 24;  // default framing: a pixel spans stitches
    so.detail = d;
    int lastIndex = -1, total = 0;
    so.progress = [&](const std::string&, int index, int n) { lastIndex = index, total = n; };
    const Scene far = buildScene(so);
    ASSERT_TRUE(far.detail().has_value());
    // Progress counts only the stages that ran: the last one is the last of the total.
    EXPECT_EQ(lastIndex + 1, total);
    EXPECT_EQ(size_t(total), far.timings().size());
    for (DetailLevel l : far.detail()->levels.level) ASSERT_TRUE(l == DetailLevel::Surface || l == DetailLevel::Culled);
    EXPECT_EQ(far.yarns().curves.curveCount(), 0u);
    EXPECT_EQ(far.plies().curves.curveCount(), 0u);
    std::vector<std::string> stages;
    for (const StageTime& t : far.timings()) stages.push_back(t.stage);
    for (const char* skipped : {"tiling", "stitch", "binding", "evaluate"})
        EXPECT_EQ(std::count(stages.begin(), stages.end(), skipped), 0) << skipped;
    // The scene with every yarn: the same framing, and its yarns cut by the same levels leave no
    // piece and the same surface triangles.
    SceneOptions fullOptions = so;
    fullOptions.detail.reset();
    fullOptions.buildPlies = false;
    const Scene full = buildScene(fullOptions);
    EXPECT_EQ(far.detail()->margin, yarnMargin(full.binding(), full.yarnRadius()));
    const View framed = frameMesh(full.mesh(), yarnMargin(full.binding(), full.yarnRadius()), d.viewSettings);
    EXPECT_EQ(far.detail()->view.eye, framed.eye);
    EXPECT_EQ(far.detail()->view.target, framed.target);
    const LevelPieces withYarns =
        splitByLevel(full.yarns(), full.binding(), full.mesh(), full.grid(), far.detail()->levels);
    EXPECT_EQ(far.detail()->pieces.surfaceFaces, withYarns.surfaceFaces);
    EXPECT_EQ(withYarns.plies.curves.curveCount() + withYarns.yarns.curves.curveCount(), 0u);
}

// The margin from the pattern (before any yarn exists) is the binding's, bit for bit, on meshes
// wider than a tile.
TEST(Detail, patternMarginIsTheBindingsMargin) {
    for (const char* mesh : {"plane", "cylinder", "sphere", "drape"}) {
        SCOPED_TRACE(mesh);
        SceneOptions so;
        so.mesh = mesh;
        so.placement.repeats = {12, 8};
        so.buildPlies = false;
        const Scene s = buildScene(so);
        EXPECT_EQ(s.yarnMargin(), yarnMargin(s.binding(), s.yarnRadius()));
        EXPECT_EQ(yarnMargin(s.pattern(), s.placement().scale, s.yarnRadius()),
                  yarnMargin(s.binding(), s.yarnRadius()));
    }
}

// The plies of ply-level pieces are the full scene's plies point for point (twist phase and frames
// from the yarn's start, not the piece's), and each piece's plies reach past both ends of its span.
TEST(Detail, plyLevelPliesAreTheFullScenesPliesPointForPoint) {
    for (const char* mesh : {"plane", "cylinder"}) {  // open courses; closed loops round the cylinder
        SCOPED_TRACE(mesh);
        const PieceCase pc = alternatingLevels(true, mesh);
        const Scene& s = pc.scene;
        const LevelPieces pieces = splitByLevel(s.yarns(), s.binding(), s.mesh(), s.grid(), pc.levels);
        const Plies full = makePlies(s.yarns(), s.plyOptions());
        const Plies cut = piecePlies(s.yarns(), pieces.plySpans, s.plyOptions());
        ASSERT_EQ(pieces.plySpans.size(), pieces.plies.curves.curveCount());
        const uint32_t n = uint32_t(resolvePlyOptions(s.plyOptions()).count);
        ASSERT_EQ(cut.curves.curveCount(), n * pieces.plySpans.size());
        const size_t partial = test::expectEveryCurveIsARunOfTheFullPly(full, cut);
        EXPECT_GT(partial, 10u);  // most pieces are cut out of longer yarns
        // Each piece's plies reach past its span: the piece's end points lie within the ply 0 curve's
        // centreline extent (the centre is the mean of the plies' points at one index).
        for (size_t k = 0; k < pieces.plySpans.size(); ++k) {
            const uint32_t c = uint32_t(k * n);
            const Polylines& p = pieces.plies.curves;
            auto centre = [&](uint32_t i) {
                glm::dvec3 m(0.0);
                for (uint32_t q = 0; q < n; ++q) m += cut.curves.points[cut.curves.begin(c + q) + i];
                return m / double(n);
            };
            const glm::dvec3 a = centre(0), b = centre(cut.curves.size(c) - 1);
            const glm::dvec3 first = p.points[p.begin(k)], last = p.points[p.end(k) - 1];
            const glm::dvec3 along = glm::normalize(centre(1) - a),
                             back = glm::normalize(centre(cut.curves.size(c) - 2) - b);
            EXPECT_GE(glm::dot(first - a, along), -1e-12) << "piece " << k << " starts before its plies";
            EXPECT_GE(glm::dot(last - b, back), -1e-12)
                << "piece " << k << " ends after its plies: span " << pieces.plySpans[k].begin << ".."
                << pieces.plySpans[k].end << " of yarn " << pieces.plySpans[k].yarn << " ("
                << s.yarns().curves.size(pieces.plySpans[k].yarn) << " vertices, closed "
                << int(s.yarns().curves.isClosed(pieces.plySpans[k].yarn)) << "), " << cut.curves.size(c)
                << " ply points";
        }
        if (std::string(mesh) == "cylinder") {  // some pieces run over a closed yarn's first vertex
            size_t wrapping = 0;
            for (const YarnSpan& span : pieces.plySpans)
                wrapping +=
                    span.end > s.yarns().curves.size(span.yarn) || span.begin >= s.yarns().curves.size(span.yarn);
            EXPECT_GT(wrapping, 0u);
        }
    }
}

}  // namespace
}  // namespace knit
