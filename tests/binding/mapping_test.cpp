#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "binding/binding_evaluate_simd.hpp"
#include "binding/binding_float.hpp"
#include "binding/binding_gather.hpp"
#include "common/fixtures.hpp"
#include "knit/binding.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/uv_grid.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

SceneOptions yarnsOnly(glm::dvec2 repeats) {
    SceneOptions o;
    o.placement.repeats = repeats;
    o.buildPlies = false;
    return o;
}

TEST(Mapping, planeMapsUvhToXyhUnderAnyTriangulation) {
    const double size = 0.1;
    for (auto kind : {test::Triangulation::Regular, test::Triangulation::Random, test::Triangulation::Slivers}) {
        const BaseMesh mesh = test::planeMesh(kind, 9, size);
        const Scene s = buildScene(loadPyp(test::sharedPattern("stocktiny.pyp")), mesh, yarnsOnly({7, 11}));
        const UvYarns& uvYarns = s.stages().uvYarns;
        ASSERT_GT(uvYarns.vertexCount(), 1000u);
        // Every tiled vertex inside the square maps to (u*size, v*size, h) to 1e-9 relative.
        Binding single;
        std::vector<glm::dvec3> expected;
        for (size_t i = 0; i < uvYarns.vertexCount(); ++i) {
            const LocateResult r = locatePoint(s.mesh(), s.grid(), uvYarns.uv[i], 0.0);
            if (r.status != LocateStatus::Inside) continue;
            single.face.push_back(r.point.face);
            single.bary.emplace_back(r.point.bary.y, r.point.bary.z);
            single.height.push_back(uvYarns.height[i]);
            single.twist.push_back(0);
            expected.emplace_back(uvYarns.uv[i].x * size, uvYarns.uv[i].y * size, uvYarns.height[i]);
        }
        single.offsets = {0, uint32_t(single.face.size())};
        single.closed = {0};
        MappedYarns mapped;
        evaluateBinding(single, s.mesh().faces, s.mesh().positions, s.normals(), mapped);
        double worst = 0;
        for (size_t i = 0; i < expected.size(); ++i)
            worst = std::max(worst, glm::length(mapped.curves.points[i] - expected[i]) / size);
        EXPECT_LT(worst, 1e-9) << "triangulation " << int(kind);
        // The bound yarns stay on the square and keep their heights.
        for (const glm::dvec3& p : s.yarns().curves.points) {
            ASSERT_GE(p.x, -1e-12);
            ASSERT_LE(p.x, size + 1e-12);
            ASSERT_GE(p.y, -1e-12);
            ASSERT_LE(p.y, size + 1e-12);
        }
    }
}

TEST(Mapping, yarnsOnPlaneEndOnlyAtTheDomainBoundary) {
    const Scene s =
        buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Random, 6), yarnsOnly({6, 9}));
    ASSERT_GT(s.bindStats().openEnds, 0u);
    EXPECT_EQ(s.bindStats().weldedEnds, 0u);
    const Polylines& c = s.yarns().curves;
    for (size_t y = 0; y < c.curveCount(); ++y) {
        ASSERT_FALSE(c.isClosed(y));
        for (const glm::dvec3 end : {c.points[c.begin(y)], c.points[c.end(y) - 1]}) {
            const glm::dvec2 uv = glm::dvec2(end) / 0.1;
            const double toBoundary = std::min(std::min(uv.x, 1 - uv.x), std::min(uv.y, 1 - uv.y));
            EXPECT_LT(std::abs(toBoundary), 1e-9) << "yarn " << y << " ends inside the square";
        }
    }
}

TEST(Mapping, cylinderPutsHeightAtRadiusPlusH) {
    ProceduralMeshOptions mo;
    mo.resU = 64;
    mo.resV = 8;
    mo.radius = 0.05;
    mo.height = 0.1;
    const Scene s = buildScene(loadPyp(test::sharedPattern("stockinette.pyp")), makeCylinder(mo), yarnsOnly({10, 6}));
    const double chord = mo.radius * (1 - std::cos(util::kPi / mo.resU));
    const Binding& b = s.binding();
    ASSERT_GT(b.vertexCount(), 0u);
    double worst = 0;
    for (size_t i = 0; i < b.vertexCount(); ++i) {
        const glm::dvec3 p = s.yarns().curves.points[i];
        const double r = std::hypot(p.x, p.z);  // the cylinder stands along +y
        worst = std::max(worst, std::abs(r - (mo.radius + b.height[i])) - chord);
    }
    EXPECT_LE(worst, 1e-12) << "radius error beyond the chord error " << chord;
}

TEST(Mapping, cylinderSeamWithIntegralRepeatsClosesCourses) {
    ProceduralMeshOptions mo;
    mo.resU = 48;
    mo.resV = 12;
    const Pattern p = generateStockinette();
    const double V = 8;
    const Scene s = buildScene(p, makeCylinder(mo), yarnsOnly({20, V}));
    // Course j spans y in [j*py - h, j*py + h] with h = 4 model units = py * 4/4.5: it lies
    // inside v in [0,1] for j = 1..7, and only those close.
    EXPECT_EQ(s.bindStats().closedLoops, 7u);
    EXPECT_GT(s.bindStats().weldedEnds, 0u);
    // Non-integral repeats around the seam: nothing meets again, nothing closes.
    const Scene t = buildScene(p, makeCylinder(mo), yarnsOnly({20.5, V}));
    EXPECT_EQ(t.bindStats().closedLoops, 0u);
}

TEST(Mapping, mappedYarnsHaveNoLongStepsAcrossTriangleEdgesAndSeams) {
    for (const char* mesh : {"cylinder", "drape", "sphere"}) {
        SceneOptions o = yarnsOnly({16, 8});
        o.mesh = mesh;
        const Scene s = buildScene(o);
        const Polylines& c = s.yarns().curves;
        // Local sampling: the step of the same pair in pattern space, scaled to the mesh.
        double longestPattern = 0;
        const PatternAdjacency adj = buildAdjacency(s.pattern());
        for (const PeriodicEdge& e : s.pattern().edges) {
            const glm::dvec2 d = glm::dvec2(s.pattern().points[e.v1]) +
                                 glm::dvec2(e.dx * s.pattern().px, e.dy * s.pattern().py) -
                                 glm::dvec2(s.pattern().points[e.v0]);
            longestPattern = std::max(longestPattern, glm::length(d));
        }
        const glm::dvec2 metresPerUv = uvToMetreScale(s.mesh());
        const double stretch = std::max(metresPerUv.x / (s.placement().repeats.x * s.pattern().px),
                                        metresPerUv.y / (s.placement().repeats.y * s.pattern().py));
        const double local = longestPattern * stretch + 2 * s.yarnRadius();  // + height offsets
        for (size_t y = 0; y < c.curveCount(); ++y)
            for (uint32_t k = 0; k < c.segmentCount(y); ++k) {
                const double step = glm::distance(c.points[c.begin(y) + k], c.points[c.begin(y) + (k + 1) % c.size(y)]);
                ASSERT_LE(step, 2 * local) << mesh << " yarn " << y << " segment " << k;
            }
    }
}

TEST(Mapping, bindingEvaluatedOnDeformedCopyEqualsFreshMapping) {
    ProceduralMeshOptions mo;
    mo.resU = 24;
    mo.resV = 24;
    const BaseMesh rest = makeDrape(mo);
    BaseMesh bent = rest;
    for (glm::dvec3& x : bent.positions) x = glm::dvec3(x.x * 1.1 + 0.3 * x.z, x.y + 0.2 * x.x * x.x, x.z * 0.9 + 0.05);
    // Heights keep the rest pose's physical scale under animation, so the fresh mapping binds
    // the same stitched yarns (same placement) directly on the deformed copy.
    const Scene a = buildScene(generateStockinette(), rest, yarnsOnly({12, 12}));
    const std::vector<glm::dvec3> bentNormals = vertexNormals(bent.positions, bent.faces);
    BindOptions bind;
    bind.yarnRadius = a.yarnRadius();
    const BindResult fresh = bindYarns(bent, bentNormals, a.grid(), a.stages().uvYarns, bind);
    MappedYarns mapped;
    evaluateBinding(fresh.binding, bent.faces, bent.positions, bentNormals, mapped);
    MappedYarns animated;
    evaluateBinding(a.binding(), bent.faces, bent.positions, bentNormals, animated);
    ASSERT_EQ(animated.curves.pointCount(), mapped.curves.pointCount());
    ASSERT_EQ(animated.curves.offsets, mapped.curves.offsets);
    double worst = 0;
    for (size_t i = 0; i < animated.curves.pointCount(); ++i)
        worst = std::max(worst, glm::distance(animated.curves.points[i], mapped.curves.points[i]));
    EXPECT_LT(worst, 1e-12);
}

// bindYarns fills its per-vertex tables from the yarn offsets: UvYarns whose offsets, heights,
// twists or ghosts disagree with the vertices are refused before anything is read.
TEST(Mapping, inconsistentUvYarnsAreRejected) {
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 6;
    const Scene a = buildScene(generateStockinette(), makeDrape(mo), yarnsOnly({3, 3}));
    BindOptions bind;
    bind.yarnRadius = a.yarnRadius();
    ASSERT_NO_THROW(bindYarns(a.mesh(), a.normals(), a.grid(), a.stages().uvYarns, bind));
    std::vector<UvYarns> broken(5, a.stages().uvYarns);
    broken[0].offsets.back() -= 1;                              // last vertex owned by no yarn
    broken[1].offsets.push_back(broken[1].offsets.back() + 3);  // a yarn past the end
    std::swap(broken[2].offsets[1], broken[2].offsets[2]);      // decreasing
    broken[3].height.pop_back();
    broken[4].ghosts.pop_back();
    for (size_t k = 0; k < broken.size(); ++k) {
        try {
            bindYarns(a.mesh(), a.normals(), a.grid(), broken[k], bind);
            ADD_FAILURE() << "case " << k << ": expected knit::Error";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("do not match their vertices"), std::string::npos) << e.what();
        }
    }
}

TEST(Mapping, floatEvaluationFarFromOriginKeepsPrecision) {
    // A drape 100 km from the origin: float32 positions relative to a local origin, computed in
    // float32, agree with the double evaluation to float precision of the garment's own size
    // (measured 4.1e-8 m: a few float32 roundings of ~0.5 m coordinates).
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    BaseMesh far = makeDrape(mo);
    const glm::dvec3 offset(1e5, -2e5, 3e4);
    for (glm::dvec3& x : far.positions) x += offset;
    const Scene s = buildScene(generateStockinette(), far, yarnsOnly({20, 20}));
    std::vector<glm::vec3> local;
    evaluateBindingFloat(s.binding(), s.mesh().faces, s.mesh().positions, s.normals(), offset, local);
    ASSERT_EQ(local.size(), s.yarns().curves.pointCount());
    double worst = 0;
    for (size_t i = 0; i < local.size(); ++i)
        worst = std::max(worst, glm::distance(glm::dvec3(local[i]) + offset, s.yarns().curves.points[i]));
    EXPECT_LT(worst, 1e-7);  // float32 of ~0.5 m coordinates: 3e-8 m per rounding
    EXPECT_LT(worst, 1e-3 * s.yarnRadius());
}

// The packed float32 evaluation agrees with the double one to float32 rounding at the garment's
// size, far from the origin too, and a pose that moves the mesh moves its yarns the same way.
TEST(Mapping, packedFloatEvaluationIsTheDoubleOneToFloatRounding) {
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    BaseMesh far = makeDrape(mo);
    const glm::dvec3 offset(1e5, -2e5, 3e4);
    for (glm::dvec3& x : far.positions) x += offset;
    const Scene s = buildScene(generateStockinette(), far, yarnsOnly({20, 20}));
    const PackedBinding packed = packBinding(s.binding());
    ASSERT_EQ(packed.vertices.size(), s.binding().vertexCount());
    std::vector<glm::vec3> local;
    evaluatePackedFloat(packed, s.mesh().faces, s.mesh().positions, s.normals(), offset, local);
    ASSERT_EQ(local.size(), s.yarns().curves.pointCount());
    double worst = 0;
    for (size_t i = 0; i < local.size(); ++i)
        worst = std::max(worst, glm::distance(glm::dvec3(local[i]) + offset, s.yarns().curves.points[i]));
    EXPECT_LT(worst, 2e-6 * 0.5);  // float32 arithmetic on ~0.5 m coordinates
    EXPECT_LT(worst, 2e-3 * s.yarnRadius());
    // A moved pose: the packed evaluation follows it as the double one does.
    std::vector<glm::dvec3> moved = s.mesh().positions;
    for (glm::dvec3& x : moved) x += glm::dvec3(0.0, 0.0, 0.05 * std::sin(8.0 * (x.x - offset.x)));
    const std::vector<glm::dvec3> movedNormals = vertexNormals(moved, s.mesh().faces);
    MappedYarns exact;
    evaluateBinding(s.binding(), s.mesh().faces, moved, movedNormals, exact);
    evaluatePackedFloat(packed, s.mesh().faces, moved, movedNormals, offset, local);
    worst = 0;
    for (size_t i = 0; i < local.size(); ++i)
        worst = std::max(worst, glm::distance(glm::dvec3(local[i]) + offset, exact.curves.points[i]));
    EXPECT_LT(worst, 2e-3 * s.yarnRadius());
    EXPECT_THROW(evaluatePackedFloat(packed, s.mesh().faces, moved, {}, offset, local), Error);
}

// The double evaluation (four vertices at a time in AVX2 where the CPU has it) is the scalar
// gather's result bit for bit, on a moved pose, with normals that cancel or vanish, and for any
// start and end of a range (the groups of four and the scalar rest).
TEST(Mapping, evaluationIsTheScalarGatherBitForBit) {
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    const Scene s = buildScene(generateStockinette(), makeDrape(mo), yarnsOnly({40, 40}));
    const Binding& b = s.binding();
    ASSERT_GT(b.vertexCount(), 20000u);  // more than one parallel block
    std::vector<glm::dvec3> moved = s.mesh().positions;
    for (glm::dvec3& x : moved) x += glm::dvec3(0.0, 0.0, 0.05 * std::sin(8.0 * x.x));
    std::vector<glm::dvec3> normals = vertexNormals(moved, s.mesh().faces);
    for (size_t v = 0; v < normals.size(); v += 3) normals[v] = -normals[v];  // some sums near zero
    std::vector<glm::dvec3> zero(normals.size(), glm::dvec3(0.0));            // every sum zero: (0, 0, 1)
    const auto same = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    for (const std::vector<glm::dvec3>* n : {&normals, &zero}) {
        MappedYarns out;
        evaluateBinding(b, s.mesh().faces, moved, *n, out);
        const BindingGather gather(b, s.mesh().faces, moved, *n);
        size_t differ = 0;
        for (size_t i = 0; i < b.vertexCount(); ++i) {
            glm::dvec3 p, nn;
            gather(i, p, nn);
            differ += !same(out.curves.points[i], p) || !same(out.normals[i], nn);
        }
        EXPECT_EQ(differ, 0u);
        // The kernel on ranges starting and ending anywhere: it does whole groups of four and
        // leaves the rest, writing nothing outside [begin, returned end).
        if (!impl::evaluateSimdAvailable()) continue;
        const impl::GatherArrays arrays{b.face.data(),         b.bary.data(), b.height.data(),
                                        s.mesh().faces.data(), moved.data(),  n->data()};
        for (size_t begin : {0, 1, 3}) {
            for (size_t end : {begin + 3, begin + 4, begin + 9, begin + 4003}) {
                std::vector<glm::dvec3> P(end + 1, glm::dvec3(7.0)), N(end + 1, glm::dvec3(7.0));
                const size_t done = impl::evaluateDoubleSimd(arrays, begin, end, P.data(), N.data());
                EXPECT_EQ(done, begin + (end - begin) / 4 * 4);
                for (size_t i = 0; i <= end; ++i) {
                    glm::dvec3 p(7.0), nn(7.0);
                    if (i >= begin && i < done) gather(i, p, nn);
                    EXPECT_TRUE(same(P[i], p) && same(N[i], nn)) << "vertex " << i;
                }
            }
        }
    }
}

// The float32 evaluation (eight vertices at a time in AVX2 where the CPU has it) is the scalar
// float32 gather's result bit for bit, from the binding's arrays and from packed records alike,
// on a moved pose, with normals that cancel or vanish, and for any start and end of a range.
TEST(Mapping, floatEvaluationIsTheScalarFloatGatherBitForBit) {
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    const Scene s = buildScene(generateStockinette(), makeDrape(mo), yarnsOnly({40, 40}));
    const Binding& b = s.binding();
    ASSERT_GT(b.vertexCount(), 20000u);  // more than one parallel block
    const PackedBinding packed = packBinding(b);
    std::vector<glm::dvec3> moved = s.mesh().positions;
    for (glm::dvec3& x : moved) x += glm::dvec3(0.0, 0.0, 0.05 * std::sin(8.0 * x.x));
    std::vector<glm::dvec3> normals = vertexNormals(moved, s.mesh().faces);
    for (size_t v = 0; v < normals.size(); v += 3) normals[v] = -normals[v];  // some sums near zero
    std::vector<glm::dvec3> zero(normals.size(), glm::dvec3(0.0));            // every sum zero: (0, 0, 1)
    const glm::dvec3 origin(0.1, -0.2, 0.3);
    const auto same = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    for (const std::vector<glm::dvec3>* n : {&normals, &zero}) {
        std::vector<glm::vec3> local, fromPacked;
        evaluateBindingFloat(b, s.mesh().faces, moved, *n, origin, local);
        evaluatePackedFloat(packed, s.mesh().faces, moved, *n, origin, fromPacked);
        const std::unique_ptr<impl::FloatCorner[]> corners = impl::floatCorners(moved, *n, origin);
        impl::FloatGatherArrays arrays;
        arrays.face = b.face.data();
        arrays.bary = b.bary.data();
        arrays.height = b.height.data();
        arrays.tri = s.mesh().faces.data();
        arrays.corner = corners.get();
        impl::FloatGatherArrays packedArrays = arrays;
        packedArrays.packed = packed.vertices.data();
        size_t differ = 0;
        for (size_t i = 0; i < b.vertexCount(); ++i) {
            const glm::vec3 f = impl::gatherFloat(arrays, i);
            differ += !same(local[i], f) || !same(fromPacked[i], f) || !same(impl::gatherFloat(packedArrays, i), f);
        }
        EXPECT_EQ(differ, 0u);
        if (!impl::evaluateFloatSimdAvailable()) continue;
        for (const impl::FloatGatherArrays* a : {&arrays, &packedArrays}) {
            for (size_t begin : {0, 1, 7}) {
                for (size_t end : {begin + 7, begin + 8, begin + 17, begin + 4003}) {
                    std::vector<glm::vec3> F(end + 1, glm::vec3(7.0f));
                    const size_t done = impl::evaluateFloatSimd(*a, begin, end, F.data());
                    EXPECT_EQ(done, begin + (end - begin) / 8 * 8);
                    for (size_t i = 0; i <= end; ++i) {
                        const glm::vec3 f = i >= begin && i < done ? impl::gatherFloat(*a, i) : glm::vec3(7.0f);
                        EXPECT_TRUE(same(F[i], f)) << "vertex " << i;
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace knit
