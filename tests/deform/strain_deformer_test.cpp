// Applying strain tables: zero strain is the geometric mapping bit for bit, a rigid motion moves
// the result rigidly, stretch along the courses shortens the loops across them, displacements are
// continuous across triangle edges, and degenerate triangles and out-of-table strains are counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/fixtures.hpp"
#include "test_util.hpp"
#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

using glm::dvec3;

// A smooth made-up table for the stockinette (24 vertices): displacements up to a third of the
// yarn radius, linear in the strain, so that interpolation is exact.
std::shared_ptr<const StrainTable> syntheticTable() {
    auto t = std::make_shared<StrainTable>();
    const Pattern p = generateStockinette();
    t->source = "synthetic.npy";
    t->axes = {std::vector<double>{-0.2, 0.4, 1.0}, std::vector<double>{-0.7, 0.0, 0.7},
               std::vector<double>{-0.2, 0.4, 1.0}};
    t->vertexCount = p.points.size();
    t->px = p.px;
    t->py = p.py;
    const size_t nx = 3, na = 3, ny = 3;
    t->data.resize(4 * t->vertexCount * nx * na * ny);
    for (size_t v = 0; v < t->vertexCount; ++v)
        for (size_t iy = 0; iy < ny; ++iy)
            for (size_t ia = 0; ia < na; ++ia)
                for (size_t ix = 0; ix < nx; ++ix) {
                    const double sx = t->axes[0][ix], sa = t->axes[1][ia], sy = t->axes[2][iy];
                    const double k = 1e-4 * double(1 + v % 3);
                    float* row = &t->data[4 * (ix + nx * ia + nx * na * iy + nx * na * ny * v)];
                    row[0] = float(k * (sx + 0.5 * sa));
                    row[1] = float(k * (sy - sx));
                    row[2] = float(2e-4 * sx);
                    row[3] = 0.0F;
                }
    return t;
}

Scene planeScene(DeformMode mode, std::shared_ptr<const StrainTable> table, int n = 8) {
    SceneOptions o;
    o.buildPlies = false;
    o.deform.mode = mode;
    o.deform.table = std::move(table);
    return buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, n, 0.05), o);
}

std::vector<dvec3> posed(const Scene& s, const std::function<dvec3(const dvec3&)>& f) {
    std::vector<dvec3> out;
    for (const dvec3& p : s.mesh().positions) out.push_back(f(p));
    return out;
}

AnimationFrame evaluateOn(const Scene& s, const std::vector<dvec3>& positions) {
    AnimatorOptions ao;
    ao.plies = false;
    ao.stats = true;
    const Animator a(s, ao);
    AnimationFrame f;
    a.evaluate(positions, f);
    return f;
}

TEST(StrainDeformer, zeroStrainIsTheGeometricMappingBitForBit) {
    const Scene none = planeScene(DeformMode::None, nullptr);
    const Scene strain = planeScene(DeformMode::Strain, syntheticTable());
    const std::vector<dvec3>& a = none.yarns().curves.points;
    const std::vector<dvec3>& b = strain.yarns().curves.points;
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 500U);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(dvec3)), 0);
    EXPECT_EQ(strain.deformStats().vertices, 0U);
    EXPECT_EQ(strain.deformStats().degenerate, 0U);
    EXPECT_EQ(strain.deformStats().total, a.size());
}

TEST(StrainDeformer, rigidMotionChangesNothingButTheMotion) {
    const Scene s = planeScene(DeformMode::Strain, syntheticTable());
    const auto strained = [](const dvec3& p) {
        return dvec3(1.3 * p.x + 0.2 * p.y, 0.9 * p.y, 0.004 * std::sin(60 * p.x));
    };
    const glm::dmat3 R(glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(dvec3(1, 2, 3))));
    const dvec3 t(3, -2, 0.5);
    const AnimationFrame a = evaluateOn(s, posed(s, strained));
    const AnimationFrame b = evaluateOn(s, posed(s, [&](const dvec3& p) { return R * strained(p) + t; }));
    ASSERT_GT(a.deform.vertices, a.deform.total / 2);  // the pose is strained: the table acts
    EXPECT_EQ(a.deform.vertices, b.deform.vertices);
    double worst = 0;
    for (size_t i = 0; i < a.yarns.curves.points.size(); ++i)
        worst = std::max(worst, glm::length(b.yarns.curves.points[i] - (R * a.yarns.curves.points[i] + t)));
    EXPECT_LT(worst, 1e-12 * 4);
    EXPECT_NEAR(a.stats.yarnLengthRatio, b.stats.yarnLengthRatio, 1e-12);
}

// Per course yarn, its extent across the courses (y on the plane), averaged over the long yarns.
double meanExtentAcross(const Polylines& yarns) {
    double sum = 0;
    int count = 0;
    for (size_t y = 0; y < yarns.curveCount(); ++y) {
        if (yarns.end(y) - yarns.begin(y) < 40) continue;
        double lo = 1e9, hi = -1e9;
        for (uint32_t i = yarns.begin(y); i < yarns.end(y); ++i) {
            lo = std::min(lo, yarns.points[i].y);
            hi = std::max(hi, yarns.points[i].y);
        }
        sum += hi - lo;
        ++count;
    }
    return count ? sum / count : 0;
}

TEST(StrainDeformer, stretchAlongCoursesShortensLoopsAcrossThem) {
    StrainTableOptions o;
    o.samples = {2, 2, 2};
    o.sxRange = {0.0, 0.6};
    o.saRange = {-0.05, 0.05};
    o.syRange = {-0.05, 0.05};
    auto table = std::make_shared<const StrainTable>(makeStrainTable(generateStockinette(), o));
    const Scene none = planeScene(DeformMode::None, nullptr);
    const Scene strain = planeScene(DeformMode::Strain, table);
    const auto stretch = [](const dvec3& p) { return dvec3(1.5 * p.x, p.y, p.z); };
    const AnimationFrame g = evaluateOn(none, posed(none, stretch));
    const AnimationFrame d = evaluateOn(strain, posed(strain, stretch));
    const double r = none.yarnRadius();
    EXPECT_LT(meanExtentAcross(d.yarns.curves), meanExtentAcross(g.yarns.curves) - 0.2 * r);
    EXPECT_LT(d.stats.yarnLengthRatio, g.stats.yarnLengthRatio - 0.05);
    EXPECT_GT(d.stats.yarnLengthRatio, 1.0);
    EXPECT_EQ(d.deform.clamped, 0U);
}

// The same pattern vertex placed on a shared edge from either triangle gets the same displacement.
TEST(StrainDeformer, displacementIsContinuousAcrossTriangleEdges) {
    const Scene s = planeScene(DeformMode::None, nullptr, 6);
    const BaseMesh& mesh = s.mesh();
    std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, int>>> edges;
    for (uint32_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back({f, k});
        }
    Binding bind;
    const auto baryOf = [&](uint32_t f, uint32_t a, uint32_t b) {
        glm::dvec3 w(0.0);
        for (int k = 0; k < 3; ++k)
            if (mesh.faces[f][k] == a || mesh.faces[f][k] == b) w[k] = 0.5;
        return glm::dvec2(w.y, w.z);
    };
    uint32_t id = 0;
    for (const auto& [e, faces] : edges) {
        if (faces.size() != 2) continue;
        for (const auto& fk : faces) {
            bind.face.push_back(fk.first);
            bind.bary.push_back(baryOf(fk.first, e.first, e.second));
            bind.height.push_back(0.0);
            bind.twist.push_back(0.0);
            bind.source.push_back(id);
        }
        ++id;
    }
    bind.offsets = {0, uint32_t(bind.face.size())};
    bind.closed = {0};
    const std::vector<dvec3> pose = posed(s, [](const dvec3& p) { return dvec3(p.x + 6 * p.x * p.x, p.y, 0.0); });
    for (const StrainLookupSite site : {StrainLookupSite::MeshVertices, StrainLookupSite::YarnVertices}) {
        const StrainDeformer deformer(mesh, s.pattern(), s.placement(), bind, syntheticTable(), site);
        MappedYarns y;
        evaluateBinding(bind, mesh.faces, pose, vertexNormals(pose, mesh.faces), y);
        const std::vector<dvec3> before = y.curves.points;
        const DeformStats st = deformer.apply(bind, pose, y);
        ASSERT_GT(st.vertices, bind.vertexCount() / 2);
        const double r = s.yarnRadius();
        double jump = 0, largest = 0;
        for (size_t i = 0; i + 1 < bind.vertexCount(); i += 2) {
            const dvec3 d0 = y.curves.points[i] - before[i], d1 = y.curves.points[i + 1] - before[i + 1];
            jump = std::max(jump, glm::length(d0 - d1));
            largest = std::max(largest, glm::length(d0));
        }
        EXPECT_GT(largest, 0.05 * r) << int(site);
        EXPECT_LT(jump, 0.05 * r) << int(site);
    }
}

// The two lookup sites agree to a small fraction of the displacement on a smoothly strained pose
// (and both act); the one-pass evaluate gives the bits of evaluateBinding followed by apply.
TEST(StrainDeformer, lookupSitesAgreeAndOnePassMatchesTwo) {
    const Scene s = planeScene(DeformMode::None, nullptr);
    const BaseMesh& mesh = s.mesh();
    const Binding& bind = s.binding();
    const std::vector<dvec3> pose =
        posed(s, [](const dvec3& p) { return dvec3(1.2 * p.x + 3 * p.x * p.x, 0.95 * p.y + 0.1 * p.x, 0.0); });
    const std::vector<dvec3> normals = vertexNormals(pose, mesh.faces);
    MappedYarns geometric;
    evaluateBinding(bind, mesh.faces, pose, normals, geometric);
    std::vector<MappedYarns> out;
    for (const StrainLookupSite site : {StrainLookupSite::MeshVertices, StrainLookupSite::YarnVertices}) {
        const StrainDeformer deformer(mesh, s.pattern(), s.placement(), bind, syntheticTable(), site);
        MappedYarns two = geometric, one;
        const DeformStats a = deformer.apply(bind, pose, two);
        const DeformStats b = deformer.evaluate(bind, pose, normals, one);
        EXPECT_EQ(a.vertices, b.vertices);
        EXPECT_EQ(a.vertices, a.total);
        ASSERT_EQ(one.curves.points.size(), two.curves.points.size());
        EXPECT_EQ(
            std::memcmp(one.curves.points.data(), two.curves.points.data(), one.curves.points.size() * sizeof(dvec3)),
            0);
        EXPECT_EQ(one.curves.offsets, geometric.curves.offsets);
        EXPECT_EQ(std::memcmp(one.normals.data(), geometric.normals.data(), one.normals.size() * sizeof(dvec3)), 0);
        out.push_back(std::move(one));
    }
    double largest = 0, apart = 0;
    for (size_t i = 0; i < geometric.curves.points.size(); ++i) {
        largest = std::max(largest, glm::length(out[1].curves.points[i] - geometric.curves.points[i]));
        apart = std::max(apart, glm::length(out[0].curves.points[i] - out[1].curves.points[i]));
    }
    EXPECT_GT(largest, 0.05 * s.yarnRadius());
    EXPECT_LT(apart, 0.03 * largest) << apart << " of " << largest;
}

// On a strained drape of many parallel blocks, the one-pass evaluate (at the UV vertices four yarn
// vertices at a time in AVX2 where the CPU has it; KNIT_SIMD=0 the scalar loop) gives the bits and
// the counts of the scalar evaluateBinding followed by apply; without twist asked, no twist.
TEST(StrainDeformer, onePassIsTheScalarTwoPassesBitForBitOnADrape) {
    SceneOptions o;
    o.placement.repeats = {40, 40};
    o.buildPlies = false;
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    const Scene s = buildScene(generateStockinette(), makeDrape(mo), o);
    const Binding& bind = s.binding();
    ASSERT_GT(bind.vertexCount(), 30000u);  // several parallel blocks
    const std::vector<dvec3> pose = posed(s, [](const dvec3& p) { return dvec3(1.15 * p.x, p.y, p.z + 0.05 * p.x); });
    const std::vector<dvec3> normals = vertexNormals(pose, s.mesh().faces);
    const StrainDeformer deformer(s.mesh(), s.pattern(), s.placement(), bind, syntheticTable(),
                                  StrainLookupSite::MeshVertices);
    MappedYarns two, one;
    evaluateBinding(bind, s.mesh().faces, pose, normals, two);
    const DeformStats a = deformer.apply(bind, pose, two);
    const DeformStats b = deformer.evaluate(bind, pose, normals, one, false);
    EXPECT_GT(a.vertices, bind.vertexCount() / 2);
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.clamped, b.clamped);
    EXPECT_EQ(a.degenerate, b.degenerate);
    ASSERT_EQ(one.curves.points.size(), two.curves.points.size());
    EXPECT_EQ(std::memcmp(one.curves.points.data(), two.curves.points.data(), one.curves.points.size() * sizeof(dvec3)),
              0);
    EXPECT_EQ(std::memcmp(one.normals.data(), two.normals.data(), one.normals.size() * sizeof(dvec3)), 0);
    EXPECT_TRUE(one.twist.empty());
}

// Largest distance from the ends of a scene's open yarns to the polylines of another scene's yarns.
double endsOffYarns(const Polylines& ends, const Polylines& yarns) {
    double worst = 0;
    for (size_t c = 0; c < ends.curveCount(); ++c) {
        if (ends.isClosed(c) || ends.size(c) < 2) continue;
        for (const uint32_t i : {ends.begin(c), ends.end(c) - 1}) {
            double best = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < yarns.curveCount(); ++k)
                for (uint32_t j = yarns.begin(k); j + 1 < yarns.end(k); ++j) {
                    const dvec3 a = yarns.points[j], ab = yarns.points[j + 1] - a;
                    const double t = std::clamp(glm::dot(ends.points[i] - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
                    best = std::min(best, glm::length(ends.points[i] - (a + t * ab)));
                }
            worst = std::max(worst, best);
        }
    }
    return worst;
}

// A yarn cut at the mesh's edge ends partway along its cell's segment: under a uniform strain its
// end lies on the same yarn of a larger plane (where it is not cut), displaced as that segment is.
// (It used to take the whole displacement of the vertex it leaves from: off the segment by t times
// the two vertices' difference, which pressed a stiff table's cut ends into their neighbours.)
TEST(StrainDeformer, aCutYarnsEndMovesAlongItsCellSegment) {
    SceneOptions o;
    o.buildPlies = false;
    const auto stretched = [](const dvec3& p) { return dvec3(1.3 * p.x + 0.2 * p.y, 0.9 * p.y, 0.0); };
    double off[2] = {0, 0};
    for (const DeformMode mode : {DeformMode::None, DeformMode::Strain}) {
        o.deform = {mode, mode == DeformMode::Strain ? syntheticTable() : nullptr};
        const Scene small =
            buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, 8, 0.05), o);
        const Scene large =
            buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, 16, 0.1), o);
        const AnimationFrame a = evaluateOn(small, posed(small, stretched));
        const AnimationFrame b = evaluateOn(large, posed(large, stretched));
        off[mode == DeformMode::Strain ? 1 : 0] = endsOffYarns(a.yarns.curves, b.yarns.curves) / small.yarnRadius();
    }
    EXPECT_LT(off[0], 1e-6);  // the tiling is the same on both planes
    EXPECT_LT(off[1], 1e-6) << "cut ends off their segments by " << off[1] << " radii";
}

TEST(StrainDeformer, degenerateTrianglesGetNoDisplacementAndAreCounted) {
    const Scene s = planeScene(DeformMode::Strain, syntheticTable());
    const Scene none = planeScene(DeformMode::None, nullptr);
    // Vertex 40 pressed onto its neighbour: the triangles around it collapse.
    std::vector<dvec3> pose = posed(s, [](const dvec3& p) { return dvec3(1.2 * p.x, p.y, p.z); });
    pose[40] = pose[41];
    const AnimationFrame d = evaluateOn(s, pose), g = evaluateOn(none, pose);
    EXPECT_GT(d.deform.degenerate, 0U);
    size_t same = 0;
    for (size_t i = 0; i < d.yarns.curves.points.size(); ++i) {
        const uint32_t f = s.binding().face[i];
        const glm::uvec3 tri = s.mesh().faces[f];
        if (tri.x == 40 || tri.y == 40 || tri.z == 40) {
            const glm::dvec3 a = pose[tri.x], b = pose[tri.y], c = pose[tri.z];
            if (glm::length(glm::cross(b - a, c - a)) > 0) continue;  // only the collapsed ones
            EXPECT_EQ(d.yarns.curves.points[i], g.yarns.curves.points[i]);
            ++same;
        }
    }
    EXPECT_EQ(same, d.deform.degenerate);
    // Non-finite positions (the library call, which the Animator would refuse) count the same way.
    MappedYarns y = s.yarns();
    std::vector<dvec3> nan = s.mesh().positions;
    nan[40] = dvec3(std::numeric_limits<double>::quiet_NaN());
    const DeformStats st = s.deformer()->apply(s.binding(), nan, y);
    EXPECT_GT(st.degenerate, 0U);
}

TEST(StrainDeformer, strainsBeyondTheTableAreClampedAndCounted) {
    const Scene s = planeScene(DeformMode::Strain, syntheticTable());
    const AnimationFrame f = evaluateOn(s, posed(s, [](const dvec3& p) { return dvec3(2.5 * p.x, p.y, p.z); }));
    EXPECT_GT(f.deform.clamped, f.deform.total / 2);
    EXPECT_EQ(f.deform.clamped, f.deform.vertices);
}

TEST(StrainDeformer, refusesAMissingOrMismatchedTable) {
    EXPECT_NE(test::errorOf([] { planeScene(DeformMode::Strain, nullptr); }).find("strain table"), std::string::npos);
    auto t = std::make_shared<StrainTable>(*syntheticTable());
    t->vertexCount = 12;
    const std::string msg = test::errorOf([&] { planeScene(DeformMode::Strain, t); });
    EXPECT_NE(msg.find("synthetic.npy"), std::string::npos) << msg;
    EXPECT_NE(msg.find("12 cell vertices"), std::string::npos) << msg;
}

}  // namespace
}  // namespace knit
