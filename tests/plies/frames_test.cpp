// Tests for rotationMinimizingFrames (double reflection, closed-loop correction, degeneracies).
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "knit/error.hpp"
#include "knit/frames.hpp"
#include "knit/resample.hpp"
#include "plies/plies_curves.hpp"
#include "util/checks.hpp"

using glm::dvec3;
using knit::Frames;
using knit::Polylines;

namespace {

using knit::test::torusKnot;
using knit::util::finite;
using knit::util::kPi;
using knit::util::kTwoPi;

Polylines one(const std::vector<dvec3>& p, bool closed) {
    Polylines c;
    c.addCurve(p.data(), p.size(), closed);
    return c;
}

void expectOrthonormal(const Frames& f, double tol = 1e-12) {
    ASSERT_EQ(f.tangent.size(), f.normal.size());
    for (size_t i = 0; i < f.tangent.size(); ++i) {
        ASSERT_TRUE(finite(f.tangent[i]) && finite(f.normal[i])) << "point " << i;
        EXPECT_NEAR(glm::length(f.tangent[i]), 1.0, tol) << "point " << i;
        EXPECT_NEAR(glm::length(f.normal[i]), 1.0, tol) << "point " << i;
        EXPECT_NEAR(glm::dot(f.tangent[i], f.normal[i]), 0.0, tol) << "point " << i;
    }
}

// Independent double-reflection step (formulas of Wang et al. 2008), for checking outputs.
dvec3 reflectTransport(dvec3 x0, dvec3 t0, dvec3 r0, dvec3 x1, dvec3 t1) {
    const dvec3 v1 = x1 - x0;
    const double c1 = glm::dot(v1, v1);
    const dvec3 rL = r0 - (2.0 / c1) * glm::dot(v1, r0) * v1;
    const dvec3 tL = t0 - (2.0 / c1) * glm::dot(v1, t0) * v1;
    const dvec3 v2 = t1 - tL;
    const double c2 = glm::dot(v2, v2);
    return c2 < 1e-30 ? rL : rL - (2.0 / c2) * glm::dot(v2, rL) * v2;
}

double signedAngle(dvec3 from, dvec3 to, dvec3 axis) {
    return std::atan2(glm::dot(axis, glm::cross(from, to)), glm::dot(from, to));
}

std::vector<dvec3> wigglyWithHairpin() {
    std::vector<dvec3> p;
    for (int i = 0; i < 40; ++i) {
        const double t = 0.2 * i;
        p.emplace_back(0.001 * t, 0.0007 * std::sin(3 * t), 0.0004 * std::cos(5 * t));
    }
    const dvec3 tip = p.back() + dvec3(0.001, 0, 0);
    p.push_back(tip);
    p.push_back(tip - dvec3(0.001, 0, 0));  // exact reversal onto the previous point
    p.push_back(tip - dvec3(0.002, 0.0002, 0));
    for (int i = 0; i <= 12; ++i) {  // a tight U-turn, resolved by a few points
        const double a = kPi * i / 12;
        p.push_back(tip - dvec3(0.003 + 0.0005 * std::sin(a), 0.0007 - 0.0005 * std::cos(a), 0.0001 * i));
    }
    return p;
}

}  // namespace

TEST(Frames, framesDoNotFlip) {
    // A coarse wiggly polyline with an exact reversal (hairpin) and a tight U-turn, raw and
    // resampled, seeded across and within the hairpin's plane: the normal never jumps by more
    // than 90 degrees between neighbours (turns the polyline does not resolve are projected).
    const Polylines raw = one(wigglyWithHairpin(), false);
    // On the raw polyline and on its resampled version.
    knit::MappedYarns y;
    y.curves = raw;
    knit::ResampleOptions ro;
    ro.spacing = 0.0001;
    const Polylines fine = knit::resampleYarns(y, ro).curves;
    for (const Polylines* c : {&raw, &fine}) {
        for (dvec3 seed : {dvec3(0, 0, 1), dvec3(0, 1, 0)}) {  // across and in the hairpin's plane
            const std::vector<dvec3> seeds(c->pointCount(), seed);
            const Frames f = knit::rotationMinimizingFrames(*c, &seeds);
            expectOrthonormal(f);
            for (size_t i = 0; i + 1 < f.normal.size(); ++i)
                EXPECT_GT(glm::dot(f.normal[i], f.normal[i + 1]), 0.0)
                    << "flip between points " << i << " and " << i + 1;
        }
    }
}

TEST(Frames, rmfOnHelixMatchesAnalyticTwistFreeFrame) {
    // Circular helix (a cos t, a sin t, b t): curvature k = a/(a^2+b^2), torsion tau = b/(a^2+b^2),
    // speed w = sqrt(a^2+b^2). The RMF normal is the Frenet normal rotated by -tau * s about T.
    // (A Frenet frame or a frame with spurious twist fails this.)
    const double a = 0.002, b = 0.001, w = std::sqrt(a * a + b * b), tau = b / (w * w);
    const int count = 4000;
    const double t1 = 4.0 * kPi;
    std::vector<dvec3> p;
    for (int i = 0; i <= count; ++i) {
        const double t = t1 * i / count;
        p.emplace_back(a * std::cos(t), a * std::sin(t), b * t);
    }
    const Polylines c = one(p, false);
    const std::vector<dvec3> seeds(p.size(), dvec3(-1, 0, 0));  // Frenet normal at t = 0
    const Frames f = knit::rotationMinimizingFrames(c, &seeds);
    expectOrthonormal(f);
    for (int i = 0; i <= count; i += 100) {
        const double t = t1 * i / count;
        const dvec3 T(-a * std::sin(t) / w, a * std::cos(t) / w, b / w);
        const dvec3 Nf(-std::cos(t), -std::sin(t), 0.0);
        const double angle = signedAngle(Nf, f.normal[i], T);
        EXPECT_NEAR(angle, std::remainder(-tau * w * t, kTwoPi), 1e-4) << "t = " << t;
    }
}

TEST(Frames, closedLoopFramesClose) {
    const Polylines c = one(torusKnot(600, 0.01), true);
    const size_t n = c.pointCount();
    const std::vector<dvec3> seeds(n, dvec3(0, 0, 1));
    // Without the correction the transported frame does not come back to itself...
    knit::FrameOptions open;
    open.closeLoops = false;
    const Frames raw = knit::rotationMinimizingFrames(c, &seeds, open);
    const dvec3 rawEnd =
        reflectTransport(c.points[n - 1], raw.tangent[n - 1], raw.normal[n - 1], c.points[0], raw.tangent[0]);
    const double mismatch = signedAngle(rawEnd, raw.normal[0], raw.tangent[0]);
    ASSERT_GT(std::abs(mismatch), 0.1) << "test curve must have RMF holonomy";
    // ...with it, every segment (the closing one included) turns the frame by the same angle
    // per unit length relative to pure transport: the closing angle is spread along arc length.
    const Frames f = knit::rotationMinimizingFrames(c, &seeds);
    expectOrthonormal(f);
    EXPECT_NEAR(glm::length(f.normal[0] - raw.normal[0]), 0.0, 1e-15);  // start is not moved
    double length = 0.0;
    for (size_t i = 0; i < n; ++i) length += glm::length(c.points[(i + 1) % n] - c.points[i]);
    double total = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        const dvec3 moved = reflectTransport(c.points[i], f.tangent[i], f.normal[i], c.points[j], f.tangent[j]);
        const double angle = signedAngle(moved, f.normal[j], f.tangent[j]);
        const double ds = glm::length(c.points[j] - c.points[i]);
        EXPECT_NEAR(angle / ds, mismatch / length, 1e-6 * std::abs(mismatch / length)) << "segment " << i;
        total += angle;
    }
    EXPECT_NEAR(total, mismatch, 1e-9);
    // The closing segment's frame change is as small as any other's.
    const double closeDot = glm::dot(f.normal[n - 1], f.normal[0]);
    double minDot = 1.0;
    for (size_t i = 0; i + 1 < n; ++i) minDot = std::min(minDot, glm::dot(f.normal[i], f.normal[i + 1]));
    EXPECT_GE(closeDot, minDot - 1e-3);
}

TEST(Frames, repeatedPointsGiveFiniteFrames) {
    const dvec3 a(0, 0, 0), b(0.001, 0, 0), c(0.001, 0.001, 0.0005);
    Polylines curves;
    const std::vector<std::vector<dvec3>> shapes{
        {a, a, b, b, b, c, c},  // repeats inside and at both ends
        {a, a, a, a},           // all the same point
        {b},                    // single point
        {a, b, b, c, a, a},     // closed, repeats across the closing segment
        {a, b},                 // closed two-point loop (hairpins at both points)
    };
    const bool closed[] = {false, false, false, true, true};
    for (size_t i = 0; i < shapes.size(); ++i) curves.addCurve(shapes[i].data(), shapes[i].size(), closed[i]);
    const std::vector<dvec3> seeds(curves.pointCount(), dvec3(0, 0, 1));
    for (const std::vector<dvec3>* s : {&seeds, static_cast<const std::vector<dvec3>*>(nullptr)}) {
        const Frames f = knit::rotationMinimizingFrames(curves, s);
        ASSERT_EQ(f.normal.size(), curves.pointCount());
        expectOrthonormal(f);
    }
    // Repeated points share the frame of the point they repeat.
    const Frames f = knit::rotationMinimizingFrames(curves, &seeds);
    EXPECT_EQ(f.tangent[0], f.tangent[1]);
    EXPECT_NEAR(glm::length(f.normal[0] - f.normal[1]), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.normal[2] - f.normal[3]), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.normal[3] - f.normal[4]), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.tangent[0] - dvec3(1, 0, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.normal[0] - dvec3(0, 0, 1)), 0.0, 1e-15);
    // A curve that is one point keeps the seed normal.
    EXPECT_NEAR(glm::length(f.normal[7] - dvec3(0, 0, 1)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.normal[11] - dvec3(0, 0, 1)), 0.0, 1e-15);
}

TEST(Frames, straightRunKeepsSeedNormal) {
    // A straight run along a skew direction, seed not perpendicular: the normal never turns.
    const dvec3 d = glm::normalize(dvec3(1, 2, -0.5));
    std::vector<dvec3> p;
    for (int i = 0; i < 200; ++i) p.push_back(dvec3(3, -1, 2) + 0.0003 * i * d);
    const Polylines c = one(p, false);
    const dvec3 seed(0, 1, 1);
    const std::vector<dvec3> seeds(p.size(), seed);
    const Frames f = knit::rotationMinimizingFrames(c, &seeds);
    const dvec3 expected = glm::normalize(seed - glm::dot(seed, d) * d);
    for (size_t i = 0; i < p.size(); ++i) {
        EXPECT_NEAR(glm::length(f.tangent[i] - d), 0.0, 1e-12) << i;
        EXPECT_NEAR(glm::length(f.normal[i] - expected), 0.0, 1e-12) << i;
    }
    // After a bend in the plane spanned by the run and the normal, the second straight run
    // keeps one constant normal too (c2 ~ 0 branch) and the binormal never changes.
    std::vector<dvec3> bent;
    for (int i = 0; i < 50; ++i) bent.emplace_back(0.001 * i, 0, 0);
    for (int i = 1; i < 50; ++i) bent.emplace_back(0.049 + 0.001 * i, 0.0, 0.001 * i);
    const Polylines cb = one(bent, false);
    const std::vector<dvec3> up(bent.size(), dvec3(0, 0, 1));
    const Frames fb = knit::rotationMinimizingFrames(cb, &up);
    for (size_t i = 51; i < bent.size(); ++i) EXPECT_NEAR(glm::length(fb.normal[i] - fb.normal[51]), 0.0, 1e-12);
    for (size_t i = 0; i < bent.size(); ++i)
        EXPECT_NEAR(glm::length(glm::cross(fb.tangent[i], fb.normal[i]) - dvec3(0, -1, 0)), 0.0, 1e-12);
}

TEST(Frames, surfaceNormalSeedsPhase) {
    const std::vector<dvec3> p = torusKnot(100, 0.01);
    Polylines c;
    c.addCurve(p.data(), p.size(), false);
    c.addCurve(p.data(), p.size(), true);
    std::vector<dvec3> seeds(c.pointCount(), dvec3(9, 9, 9));
    const dvec3 s0(0.3, -0.2, 1.0), s1(-1.0, 0.1, 0.2);
    seeds[0] = s0;  // only the first point's seed counts
    seeds[p.size()] = s1;
    const Frames f = knit::rotationMinimizingFrames(c, &seeds);
    for (size_t k = 0; k < 2; ++k) {
        const size_t i = k * p.size();
        const dvec3 t = f.tangent[i];
        const dvec3 s = k == 0 ? s0 : s1;
        const dvec3 expected = glm::normalize(s - glm::dot(s, t) * t);
        EXPECT_NEAR(glm::length(f.normal[i] - expected), 0.0, 1e-14) << "curve " << k;
    }
    // A seed parallel to the tangent (or zero) falls back to the least aligned axis.
    const std::vector<dvec3> line{dvec3(0, 0, 0), dvec3(0, 0, 1)};
    const Polylines l = one(line, false);
    for (dvec3 bad : {dvec3(0, 0, 1), dvec3(0.0), dvec3(std::numeric_limits<double>::quiet_NaN())}) {
        const std::vector<dvec3> s(2, bad);
        const Frames g = knit::rotationMinimizingFrames(l, &s);
        expectOrthonormal(g);
        EXPECT_NEAR(glm::length(g.normal[0] - dvec3(1, 0, 0)), 0.0, 1e-15);
    }
}

TEST(Frames, framesIndependentOfThreadCount) {
    Polylines c;
    for (int k = 0; k < 64; ++k) {
        const std::vector<dvec3> p = torusKnot(200 + k, 0.01 + 0.001 * k);
        c.addCurve(p.data(), p.size(), k % 2 == 0);
    }
    const std::vector<dvec3> seeds(c.pointCount(), dvec3(0, 0, 1));
    Frames one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = knit::rotationMinimizingFrames(c, &seeds);
    }
    two = knit::rotationMinimizingFrames(c, &seeds);
    EXPECT_TRUE(one.normal == two.normal);
    EXPECT_TRUE(one.tangent == two.tangent);
}

TEST(Frames, invalidFrameInputRejected) {
    const Polylines c = one({dvec3(0, 0, 0), dvec3(1, 0, 0)}, false);
    const std::vector<dvec3> wrong(1, dvec3(0, 0, 1));
    EXPECT_THROW(knit::rotationMinimizingFrames(c, &wrong), knit::Error);
    Polylines bad = c;
    bad.points[0].x = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(knit::rotationMinimizingFrames(bad, nullptr), knit::Error);
}
