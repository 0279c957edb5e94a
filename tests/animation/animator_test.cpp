// Animator: bind once on the rest pose, evaluate per frame (rest pose, rigid motion, stretch,
// statistics, buffer reuse).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/fixtures.hpp"
#include "plies/frames_curve.hpp"
#include "test_util.hpp"
#include "knit/animation.hpp"
#include "knit/binding.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "util/math.hpp"
#include "util/simd.hpp"

namespace knit {
namespace {

using glm::dvec3;

// A small knitted plane (3 x 3 repeats) with plies, bound on the rest pose.
Scene restScene(int n = 6) {
    SceneOptions o;
    o.placement.repeats = {3, 3};
    return buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, n), o);
}

std::vector<dvec3> mapped(const std::vector<dvec3>& p, const glm::dmat3& a, dvec3 t) {
    std::vector<dvec3> out;
    for (const dvec3& q : p) out.push_back(a * q + t);
    return out;
}

// The rest frame and the frame of the rest mesh mapped by x -> a x.
struct RestAndDeformed {
    AnimationFrame rest, deformed;
};
RestAndDeformed restAndDeformed(const glm::dmat3& a) {
    const Scene s = restScene();
    const Animator animator(s);
    RestAndDeformed f;
    animator.evaluate(s.mesh().positions, f.rest);
    animator.evaluate(mapped(s.mesh().positions, a, dvec3(0)), f.deformed);
    return f;
}

// On the rest pose the carried frame seed is the rest seed turned by R = I (up to rounding).
TEST(Animator, restPoseGivesTheScenesPliesToRounding) {
    const Scene s = restScene();
    const Animator animator(s);
    AnimationFrame f;
    animator.evaluate(s.mesh().positions, f);
    ASSERT_EQ(f.plies.curves.offsets, s.plies().curves.offsets);
    ASSERT_EQ(f.plies.curves.points.size(), s.plies().curves.points.size());
    for (size_t i = 0; i < f.plies.curves.points.size(); ++i)
        ASSERT_LE(glm::length(f.plies.curves.points[i] - s.plies().curves.points[i]), 1e-13) << "ply point " << i;
    EXPECT_NEAR(f.stats.maxStretch, 1.0, 1e-12);
}

// The float32 transport (AnimatorOptions::framePrecision) stays near the double frames: every
// ply point within 1e-5 yarn radii of the scene's plies on the rest pose, and it does compute
// its own frames (not bit for bit the double ones) where AVX2 is available.
TEST(Animator, floatFramesStayNearTheScenesPlies) {
    const Scene s = restScene();
    AnimatorOptions o;
    o.framePrecision = FramePrecision::Float32;
    const Animator animator(s, o);
    AnimationFrame f;
    animator.evaluate(s.mesh().positions, f);
    ASSERT_EQ(f.plies.curves.points.size(), s.plies().curves.points.size());
    double worst = 0.0;
    for (size_t i = 0; i < f.plies.curves.points.size(); ++i)
        worst = std::max(worst, glm::length(f.plies.curves.points[i] - s.plies().curves.points[i]));
    std::printf("float frames: largest ply point distance %.3g yarn radii\n", worst / s.yarnRadius());
    EXPECT_LE(worst, 1e-5 * s.yarnRadius());
    if (util::avx2Kernels()) EXPECT_GT(worst, 0.0);
}

TEST(Animator, rigidMotionMovesEveryOutputPointByExactlyThatMotion) {
    const Scene s = restScene();
    const Animator animator(s);
    AnimationFrame rest, moved;
    animator.evaluate(s.mesh().positions, rest);
    const glm::dmat3 r(glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(dvec3(1, 2, 3))));
    const dvec3 t(0.3, -0.2, 0.5);
    animator.evaluate(mapped(s.mesh().positions, r, t), moved);
    const double scale = 0.1 + glm::length(t);  // the scene's extent and the offset
    ASSERT_EQ(moved.plies.curves.points.size(), rest.plies.curves.points.size());
    for (size_t i = 0; i < rest.plies.curves.points.size(); ++i)
        ASSERT_LE(glm::length(moved.plies.curves.points[i] - (r * rest.plies.curves.points[i] + t)), 1e-9 * scale)
            << "ply point " << i;
    for (size_t i = 0; i < rest.yarns.curves.points.size(); ++i)
        ASSERT_LE(glm::length(moved.yarns.curves.points[i] - (r * rest.yarns.curves.points[i] + t)), 1e-9 * scale);
    EXPECT_NEAR(moved.stats.maxStretch, 1.0, 1e-9);
    EXPECT_NEAR(moved.stats.minYarnDistance, rest.stats.minYarnDistance, 1e-6);
}

// A 5% stretch along x: the twist phase is tied to the rest arc length, so no ply point moves
// against its yarn centre by more than a small fraction of how far the surface moves (a phase
// taken from the stretched arc length would turn the plies by up to a radius per few pitches).
TEST(Animator, stretchSequenceKeepsThePhase) {
    const RestAndDeformed f = restAndDeformed(glm::dmat3(dvec3(1.05, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, 1)));
    const AnimationFrame& rest = f.rest;
    const AnimationFrame& stretched = f.deformed;
    double surfaceMoves = 0, againstSurface = 0;
    const Plies& p0 = rest.plies;
    for (size_t c = 0; c < p0.curves.curveCount(); ++c) {
        const uint32_t y = p0.yarnOfCurve[c];
        const uint32_t centre = rest.centres.begin(y);
        for (uint32_t k = p0.curves.begin(c), j = 0; k < p0.curves.end(c); ++k, ++j) {
            const dvec3 dCentre = stretched.centres.points[centre + j] - rest.centres.points[centre + j];
            const dvec3 dPly = stretched.plies.curves.points[k] - p0.curves.points[k];
            surfaceMoves = std::max(surfaceMoves, glm::length(dCentre));
            againstSurface = std::max(againstSurface, glm::length(dPly - dCentre));
        }
    }
    EXPECT_GT(surfaceMoves, 0.0);
    EXPECT_LT(againstSurface, 0.1 * surfaceMoves);
    EXPECT_NEAR(stretched.stats.maxStretch, 1.05, 0.01);
}

TEST(Animator, compressionBringsYarnsCloser) {
    const RestAndDeformed f = restAndDeformed(glm::dmat3(dvec3(1, 0, 0), dvec3(0, 0.5, 0), dvec3(0, 0, 1)));
    const AnimationFrame& rest = f.rest;
    const AnimationFrame& squashed = f.deformed;
    ASSERT_TRUE(std::isfinite(rest.stats.minYarnDistance));
    EXPECT_LT(squashed.stats.minYarnDistance, rest.stats.minYarnDistance);
    EXPECT_LT(squashed.stats.maxStretch, 1.0 + 1e-9);
}

TEST(Animator, buffersAreReusedFromFrameToFrame) {
    const Scene s = restScene();
    const Animator animator(s);
    AnimationFrame f;
    animator.evaluate(s.mesh().positions, f);
    const dvec3* plies = f.plies.curves.points.data();
    const dvec3* yarns = f.yarns.curves.points.data();
    const dvec3* centres = f.centres.points.data();
    animator.evaluate(mapped(s.mesh().positions, glm::dmat3(1.0), dvec3(0, 0, 0.01)), f);
    EXPECT_EQ(f.plies.curves.points.data(), plies);
    EXPECT_EQ(f.yarns.curves.points.data(), yarns);
    EXPECT_EQ(f.centres.points.data(), centres);
}

// The yarns alone (the Python module's Scene.evaluate): the binding evaluated on the frame, bit
// for bit, with nothing resampled and the ply options neither needed nor checked.
TEST(Animator, yarnsAloneAreTheBindingEvaluatedWithoutPlyOptions) {
    SceneOptions o;
    o.placement.repeats = {3, 3};
    o.buildPlies = false;
    o.plies.samplesPerTurn = 1;  // invalid for plies
    const Scene s = buildScene(generateStockinette(), test::planeMesh(test::Triangulation::Regular, 6), o);
    EXPECT_THROW({ const Animator withPlies(s); }, Error);
    AnimatorOptions yarnsOnly;
    yarnsOnly.plies = false;
    yarnsOnly.stats = false;
    const Animator animator(s, yarnsOnly);
    const std::vector<dvec3> frame =
        mapped(s.mesh().positions, glm::dmat3(1.0, 0.2, 0.0, 0.0, 1.1, 0.0, 0.0, 0.3, 0.9), dvec3(0.1, 0.0, -0.2));
    AnimationFrame f;
    animator.evaluate(frame, f);
    MappedYarns expected;
    evaluateBinding(s.binding(), s.mesh().faces, frame, vertexNormals(frame, s.mesh().faces), expected);
    EXPECT_EQ(f.yarns.curves.points, expected.curves.points);
    EXPECT_EQ(f.yarns.normals, expected.normals);
    EXPECT_TRUE(f.centres.points.empty());
    EXPECT_TRUE(f.plies.curves.points.empty());
    EXPECT_EQ(animator.plyPointCount(), 0u);
}

TEST(Animator, frameWithAnotherVertexCountOrNaNIsRefused) {
    const Scene s = restScene();
    const Animator animator(s);
    AnimationFrame f;
    std::vector<dvec3> p = s.mesh().positions;
    p.pop_back();
    EXPECT_NE(test::errorOf([&] { animator.evaluate(p, f); }).find("vertices but the rest mesh"), std::string::npos);
    p = s.mesh().positions;
    p[5].y = std::nan("");
    EXPECT_EQ(test::errorOf([&] { animator.evaluate(p, f); }), "the animation frame's vertex 5 is not finite");
}

// The first tangent turns in the xz plane through the surface normal z (phi = 90 degrees): the
// projected surface normal (the old per-frame seed) flips there; the rest frame (T0 = x,
// N0 = z) carried by parallel transport turns continuously.
TEST(Animator, transportedFrameSeedDoesNotFlipWhereTheTangentPassesTheSurfaceNormal) {
    const dvec3 restTangent(1, 0, 0), restNormal(0, 0, 1);
    dvec3 lastProjected(0.0), lastTransported(0.0);
    double worstProjected = 1.0, worstTransported = 1.0;
    for (int step = 0; step <= 20; ++step) {
        const double phi = (80.5 + step) * knit::util::kPi / 180.0;  // 89.5 -> 90.5 crosses the normal
        const dvec3 x[2] = {dvec3(0.0), dvec3(std::cos(phi), 0.0, std::sin(phi))};
        dvec3 t[2], projected[2], transported[2];
        curveFrames(x, 2, false, &restNormal, t, projected);
        curveFrames(x, 2, false, &restNormal, t, transported, {}, &restTangent);
        EXPECT_NEAR(glm::length(transported[0] - dvec3(-std::sin(phi), 0.0, std::cos(phi))), 0.0, 1e-12) << phi;
        if (step > 0) {
            worstProjected = std::min(worstProjected, glm::dot(projected[0], lastProjected));
            worstTransported = std::min(worstTransported, glm::dot(transported[0], lastTransported));
        }
        lastProjected = projected[0];
        lastTransported = transported[0];
    }
    EXPECT_LT(worstProjected, 0.0);     // the flip the transport removes
    EXPECT_GT(worstTransported, 0.99);  // 1-degree steps: cos(1 degree)
}

}  // namespace
}  // namespace knit
