// Tests for makePlies / resolvePlyOptions (helix sweep, twist handedness, loop closure).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "knit/error.hpp"
#include "knit/frames.hpp"
#include "knit/plies.hpp"
#include "knit/resample.hpp"
#include "plies/plies_curves.hpp"
#include "util/checks.hpp"

using glm::dvec3;
using knit::MappedYarns;
using knit::PlyOptions;
using knit::Plies;
using knit::Twist;

namespace {

using knit::test::addYarn;
using knit::test::circle;
using knit::test::torusKnot;
using knit::util::kPi;
using knit::util::kTwoPi;

// Crane's plain-knit yarn curve (t + a sin 2t, h cos t, d cos 2t), a = 3/2, h = 4, d = 1, scaled.
std::vector<dvec3> knitCurve(double scale, int loops, int perLoop) {
    std::vector<dvec3> p;
    for (int i = 0; i <= loops * perLoop; ++i) {
        const double t = kTwoPi * i / perLoop;
        p.push_back(scale * dvec3(t + 1.5 * std::sin(2 * t), 4.0 * std::cos(t), std::cos(2 * t)));
    }
    return p;
}

MappedYarns resampledFor(const MappedYarns& y, const PlyOptions& o) {
    const PlyOptions r = knit::resolvePlyOptions(o);
    knit::ResampleOptions ro;
    ro.spacing = r.pitch / r.samplesPerTurn;
    return knit::resampleYarns(y, ro);
}

}  // namespace

TEST(Plies, helixOnStraightYarnMatchesAnalytic) {
    MappedYarns y;
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.01, 0, 0), dvec3(0.017, 0, 0), dvec3(0.035, 0, 0)}, false);
    for (Twist twist : {Twist::S, Twist::Z}) {
        PlyOptions o;
        o.count = 3;
        o.yarnRadius = 0.001;
        o.pitch = 0.006;
        o.samplesPerTurn = 16;
        o.twist = twist;
        const Plies p = knit::makePlies(y, o);
        const MappedYarns c = resampledFor(y, o);
        ASSERT_EQ(p.curves.curveCount(), 3u);
        const double R = 0.001 / (1.0 + std::sin(kPi / 3));
        EXPECT_NEAR(p.centerRadius, R, 1e-15);
        // Frame on a straight yarn along x seeded with z: T = x, N = z, B = T x N = -y.
        const double sign = twist == Twist::Z ? 1.0 : -1.0;
        for (uint32_t i = 0; i < 3; ++i) {
            EXPECT_EQ(p.yarnOfCurve[i], 0u);
            EXPECT_EQ(p.plyOfCurve[i], i);
            EXPECT_FALSE(p.curves.isClosed(i));
            ASSERT_EQ(p.curves.size(i), c.curves.size(0));
            for (uint32_t j = 0; j < c.curves.size(0); ++j) {
                const dvec3 x = c.curves.points[j];
                ASSERT_EQ(x.y, 0.0);
                ASSERT_EQ(x.z, 0.0);
                if (j > 0) {
                    ASSERT_GT(x.x, c.curves.points[j - 1].x);  // monotone: arc length = x
                }
                const double a = sign * kTwoPi * x.x / 0.006 + kTwoPi * i / 3.0;
                const dvec3 expected(x.x, -R * std::sin(a), R * std::cos(a));
                const dvec3 got = p.curves.points[p.curves.begin(i) + j];
                EXPECT_NEAR(glm::length(got - expected), 0.0, 1e-9) << "ply " << i << " point " << j;
                const dvec3 radial = p.radial[p.curves.begin(i) + j];
                EXPECT_NEAR(glm::length(radial - dvec3(0, -std::sin(a), std::cos(a))), 0.0, 1e-12);
            }
        }
        // 16 samples per turn: no centreline step longer than pitch / 16.
        for (uint32_t j = 1; j < c.curves.size(0); ++j)
            EXPECT_LE(c.curves.points[j].x - c.curves.points[j - 1].x, 0.006 / 16);
    }
}

TEST(Plies, plyCentresStayAtRadius) {
    MappedYarns y;
    addYarn(y, knitCurve(0.0005, 4, 24), false);
    PlyOptions o;
    o.count = 3;
    o.yarnRadius = 0.0004;
    const Plies p = knit::makePlies(y, o);
    const MappedYarns c = resampledFor(y, o);
    const knit::Frames f = knit::rotationMinimizingFrames(c.curves, &c.normals);
    const double R = p.centerRadius;
    ASSERT_EQ(p.curves.curveCount(), 3u);
    for (uint32_t i = 0; i < 3; ++i) {
        for (uint32_t j = 0; j < c.curves.size(0); ++j) {
            const dvec3 d = p.curves.points[p.curves.begin(i) + j] - c.curves.points[j];
            EXPECT_NEAR(glm::length(d), R, 0.01 * R) << "ply " << i << " point " << j;
            EXPECT_NEAR(glm::dot(d, f.tangent[j]), 0.0, 1e-9 * R);  // in the normal plane
            const dvec3 r = p.radial[p.curves.begin(i) + j];
            EXPECT_NEAR(glm::length(r), 1.0, 1e-12);
            EXPECT_NEAR(glm::length(d - R * r), 0.0, 1e-12 * R);
            // Plies keep their 120 degree spacing around the yarn.
            const dvec3 r0 = p.radial[p.curves.begin(0) + j];
            EXPECT_NEAR(glm::dot(r0, r), std::cos(kTwoPi * i / 3.0), 1e-12);
        }
    }
}

TEST(Plies, closedLoopPliesClose) {
    MappedYarns y;
    addYarn(y, torusKnot(300, 0.004), true, dvec3(0, 0, 1));
    PlyOptions o;
    o.count = 2;
    o.yarnRadius = 0.0005;
    o.pitch = 0.0037;  // not a divisor of the loop length
    const Plies p = knit::makePlies(y, o);
    ASSERT_EQ(p.curves.curveCount(), 2u);
    for (uint32_t i = 0; i < 2; ++i) {
        ASSERT_TRUE(p.curves.isClosed(i));
        const uint32_t b = p.curves.begin(i), n = p.curves.size(i);
        auto seg = [&](uint32_t k) { return glm::length(p.curves.points[b + (k + 1) % n] - p.curves.points[b + k]); };
        double lo = 1e9, hi = 0.0;
        for (uint32_t k = 0; k + 1 < n; ++k) {
            lo = std::min(lo, seg(k));
            hi = std::max(hi, seg(k));
        }
        const double closing = seg(n - 1);
        EXPECT_LE(closing, hi) << "ply " << i;
        EXPECT_GE(closing, lo) << "ply " << i;
        // ...and it matches its neighbours (no jump in position or in the twist).
        const double neighbours = 0.5 * (seg(n - 2) + seg(0));
        EXPECT_NEAR(closing, neighbours, 0.1 * neighbours) << "ply " << i;
        // The ply phase turns across the closing segment as much as across its neighbours.
        auto turn = [&](uint32_t k) {
            return std::acos(std::clamp(glm::dot(p.radial[b + k], p.radial[b + (k + 1) % n]), -1.0, 1.0));
        };
        const double around = 0.5 * (turn(n - 2) + turn(0));
        EXPECT_NEAR(turn(n - 1), around, 0.05 * around) << "ply " << i;
    }
}

TEST(Plies, twistClosureWithNonIntegerTurns) {
    // Circle with length / pitch = 3.4: a closed yarn rounds to 3 turns, an open one keeps 3.4.
    const std::vector<dvec3> ring = circle(0.01, 64);
    for (bool closed : {true, false}) {
        MappedYarns y;
        addYarn(y, ring, closed, dvec3(0, 0, 1));
        PlyOptions o;
        o.count = 2;
        o.yarnRadius = 0.0005;
        o.samplesPerTurn = 32;
        o.twist = Twist::S;
        o.pitch = kTwoPi * 0.01 / 3.4;
        const Plies p = knit::makePlies(y, o);
        const MappedYarns c = resampledFor(y, o);
        const knit::Frames f = knit::rotationMinimizingFrames(c.curves, &c.normals);
        const uint32_t n = c.curves.size(0);
        ASSERT_EQ(p.curves.size(0), n);
        const uint32_t steps = closed ? n : n - 1;
        double length = 0.0;
        for (uint32_t j = 0; j < steps; ++j) length += glm::length(c.curves.points[(j + 1) % n] - c.curves.points[j]);
        if (closed) {
            ASSERT_NEAR(length / o.pitch, 3.4, 0.01);
        }
        // Phase of ply 0 in its (N, B) frame; the planar circle's RMF normal stays +z.
        std::vector<double> phase(n);
        for (uint32_t j = 0; j < n; ++j) {
            ASSERT_NEAR(glm::length(f.normal[j] - dvec3(0, 0, 1)), 0.0, 1e-9);
            const dvec3 B = glm::cross(f.tangent[j], f.normal[j]);
            const dvec3 r = p.radial[j];
            phase[j] = std::atan2(glm::dot(r, B), glm::dot(r, f.normal[j]));
        }
        double total = 0.0;
        for (uint32_t j = 0; j < steps; ++j) {
            const double step = std::remainder(phase[(j + 1) % n] - phase[j], kTwoPi);
            EXPECT_LT(step, 0.0) << "S twist turns clockwise about T";
            total += step;
        }
        if (closed) {
            EXPECT_NEAR(total, -kTwoPi * 3.0, 1e-9);  // an integer number of turns
            const double closingStep = std::abs(std::remainder(phase[0] - phase[n - 1], kTwoPi));
            const double closingLength = glm::length(c.curves.points[0] - c.curves.points[n - 1]);
            EXPECT_NEAR(closingStep, kTwoPi * 3.0 * closingLength / length, 1e-9);  // no twist jump
        } else {
            EXPECT_NEAR(total, -kTwoPi * length / o.pitch, 1e-9);  // not rounded
            EXPECT_GT(std::abs(total), kTwoPi * 3.2);
        }
    }
}

TEST(Plies, sAndZTwistHaveOppositeHandedness) {
    // (1) The letter picture: yarn vertical (+z), viewer at -y looking along +y (right = +x),
    // surface normal toward the viewer so ply 0 starts on the near side. A Z strand rises to
    // the right ("/"), an S strand to the left ("\").
    MappedYarns vertical;
    addYarn(vertical, {dvec3(0, 0, 0), dvec3(0, 0, 0.02)}, false, dvec3(0, -1, 0));
    for (Twist twist : {Twist::S, Twist::Z}) {
        PlyOptions o;
        o.count = 2;
        o.twist = twist;
        const Plies p = knit::makePlies(vertical, o);
        const dvec3 a = p.curves.points[0], b = p.curves.points[1];
        EXPECT_LT(a.y, 0.0);  // near side
        EXPECT_GT(b.z - a.z, 0.0);
        if (twist == Twist::Z) EXPECT_GT(b.x - a.x, 0.0) << "Z twist must slant like '/'";
        else EXPECT_LT(b.x - a.x, 0.0) << "S twist must slant like '\\'";
    }
    // (2) Intrinsic handedness: on a straight skew yarn the discrete torsion sign
    // det(d1, d2, d3) of every ply is positive for Z (right-handed), negative for S; and on a
    // curved yarn dot(T, cross(radial, dc)) has the sign of dtheta/ds.
    MappedYarns skew;
    const dvec3 dir = glm::normalize(dvec3(1, -2, 0.5));
    addYarn(skew, {dvec3(0.1, 0.2, 0.3), dvec3(0.1, 0.2, 0.3) + 0.03 * dir}, false, dvec3(0.3, 0.5, 1));
    MappedYarns curved;
    addYarn(curved, knitCurve(0.0005, 2, 24), false);
    for (Twist twist : {Twist::S, Twist::Z}) {
        const double sign = twist == Twist::Z ? 1.0 : -1.0;
        PlyOptions o;
        o.count = 3;
        o.yarnRadius = 0.0004;
        o.twist = twist;
        const Plies p = knit::makePlies(skew, o);
        for (size_t c = 0; c < p.curves.curveCount(); ++c) {
            const dvec3* q = p.curves.points.data() + p.curves.begin(c);
            for (uint32_t j = 0; j + 3 < p.curves.size(c); ++j) {
                const double det = glm::dot(q[j + 1] - q[j], glm::cross(q[j + 2] - q[j + 1], q[j + 3] - q[j + 2]));
                EXPECT_GT(sign * det, 0.0) << "ply " << c << " point " << j;
            }
        }
        const Plies pc = knit::makePlies(curved, o);
        const MappedYarns cc = resampledFor(curved, o);
        const knit::Frames f = knit::rotationMinimizingFrames(cc.curves, &cc.normals);
        for (size_t c = 0; c < pc.curves.curveCount(); ++c) {
            const uint32_t b = pc.curves.begin(c);
            for (uint32_t j = 0; j + 1 < pc.curves.size(c); ++j) {
                const dvec3 dc = pc.curves.points[b + j + 1] - pc.curves.points[b + j];
                const dvec3 r = 0.5 * (pc.radial[b + j] + pc.radial[b + j + 1]);
                const dvec3 t = glm::normalize(f.tangent[j] + f.tangent[j + 1]);
                EXPECT_GT(sign * glm::dot(t, glm::cross(r, dc)), 0.0) << "ply " << c << " point " << j;
            }
        }
    }
}

TEST(Plies, invalidPlyOptionsRejected) {
    const std::vector<std::pair<std::function<void(PlyOptions&)>, std::string>> cases{
        {[](PlyOptions& o) { o.count = 0; }, "the number of plies"},
        {[](PlyOptions& o) { o.count = 17; }, "the number of plies"},
        {[](PlyOptions& o) { o.yarnRadius = 0.0; }, "the yarn radius"},
        {[](PlyOptions& o) { o.yarnRadius = -0.001; }, "the yarn radius"},
        {[](PlyOptions& o) { o.yarnRadius = std::numeric_limits<double>::quiet_NaN(); }, "the yarn radius"},
        {[](PlyOptions& o) { o.centerRadius = -0.001; }, "the ply centre radius"},
        {[](PlyOptions& o) { o.plyRadius = std::numeric_limits<double>::infinity(); }, "the ply radius"},
        {[](PlyOptions& o) { o.pitch = -0.01; }, "the ply pitch"},
        {[](PlyOptions& o) { o.pitch = std::numeric_limits<double>::quiet_NaN(); }, "the ply pitch"},
        {[](PlyOptions& o) { o.samplesPerTurn = 2; }, "the samples per turn"},
        {[](PlyOptions& o) { o.samplesPerTurn = 1025; }, "the samples per turn"},
        {[](PlyOptions& o) { o.twist = static_cast<Twist>(7); }, "the twist direction"},
        {[](PlyOptions& o) {
             o.count = 1;
             o.centerRadius = 0.002;
         },
         "the ply radius"},
    };
    MappedYarns y;
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.01, 0, 0)}, false);
    for (const auto& [mutate, name] : cases) {
        PlyOptions o;
        mutate(o);
        for (int call = 0; call < 2; ++call) {
            try {
                if (call == 0) knit::resolvePlyOptions(o);
                else knit::makePlies(y, o);
                ADD_FAILURE() << "accepted bad option " << name;
            } catch (const knit::Error& e) {
                EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            }
        }
    }
    // The range ends are valid.
    for (int count : {1, 16})
        for (int samples : {3, 1024}) {
            PlyOptions o;
            o.count = count;
            o.samplesPerTurn = samples;
            EXPECT_NO_THROW(knit::makePlies(y, o));
        }
}

TEST(Plies, resolvedRadiiMakeTouchingPliesThatFillTheYarn) {
    for (int n = 2; n <= 16; ++n) {
        PlyOptions o;
        o.count = n;
        o.yarnRadius = 0.002;
        const PlyOptions r = knit::resolvePlyOptions(o);
        EXPECT_NEAR(r.centerRadius + r.plyRadius, 0.002, 1e-15) << n;                          // fills the yarn
        EXPECT_NEAR(2.0 * r.centerRadius * std::sin(kPi / n), 2.0 * r.plyRadius, 1e-15) << n;  // neighbours touch
        EXPECT_EQ(r.pitch, 6.0 * 0.002);
        const PlyOptions again = knit::resolvePlyOptions(r);  // idempotent
        EXPECT_EQ(again.centerRadius, r.centerRadius);
        EXPECT_EQ(again.plyRadius, r.plyRadius);
    }
    PlyOptions two;
    two.yarnRadius = 0.002;
    const PlyOptions r2 = knit::resolvePlyOptions(two);
    EXPECT_NEAR(r2.centerRadius, 0.001, 1e-18);
    EXPECT_NEAR(r2.plyRadius, 0.001, 1e-18);
    PlyOptions one;
    one.count = 1;
    const PlyOptions r1 = knit::resolvePlyOptions(one);
    EXPECT_EQ(r1.centerRadius, 0.0);
    EXPECT_EQ(r1.plyRadius, one.yarnRadius);
    PlyOptions given;
    given.centerRadius = 0.0007;
    given.plyRadius = 0.0002;
    given.pitch = 0.01;
    const PlyOptions rg = knit::resolvePlyOptions(given);
    EXPECT_EQ(rg.centerRadius, 0.0007);
    EXPECT_EQ(rg.plyRadius, 0.0002);
    EXPECT_EQ(rg.pitch, 0.01);
}

TEST(Plies, singlePlyLiesOnTheCentreline) {
    MappedYarns y;
    addYarn(y, knitCurve(0.0005, 1, 16), false);
    PlyOptions o;
    o.count = 1;
    const Plies p = knit::makePlies(y, o);
    const MappedYarns c = resampledFor(y, o);
    ASSERT_EQ(p.curves.curveCount(), 1u);
    EXPECT_EQ(p.plyRadius, o.yarnRadius);
    EXPECT_TRUE(p.curves.points == c.curves.points);
    for (const dvec3& r : p.radial) EXPECT_NEAR(glm::length(r), 1.0, 1e-12);
}

TEST(Plies, surfaceNormalSeedsPhase) {
    // Ply 0 starts at C(0) + R * (surface normal projected perpendicular to the tangent)...
    MappedYarns y;
    addYarn(y, knitCurve(0.0005, 2, 20), false);
    const dvec3 seed = glm::normalize(dvec3(0.2, 0.4, 1.0));
    std::fill(y.normals.begin(), y.normals.end(), dvec3(0, 0, 1));
    y.normals[0] = seed;
    for (Twist twist : {Twist::S, Twist::Z}) {
        PlyOptions o;
        o.count = 4;
        o.yarnRadius = 0.0004;
        o.twist = twist;
        const Plies p = knit::makePlies(y, o);
        const MappedYarns c = resampledFor(y, o);
        const knit::Frames f = knit::rotationMinimizingFrames(c.curves, &c.normals);
        const dvec3 t = f.tangent[0];
        const dvec3 n0 = glm::normalize(seed - glm::dot(seed, t) * t);
        EXPECT_NEAR(glm::length(f.normal[0] - n0), 0.0, 1e-14);
        EXPECT_NEAR(glm::length(p.curves.points[0] - (c.curves.points[0] + p.centerRadius * n0)), 0.0, 1e-15);
        EXPECT_NEAR(glm::length(p.radial[0] - n0), 0.0, 1e-14);
    }
    // ...so a rigid motion of the yarn and its surface normals (an animated pose) moves the
    // plies rigidly: the phase does not depend on where the yarn is or how it is turned.
    const double ca = std::cos(0.7), sa = std::sin(0.7);
    const glm::dmat3 Q =
        glm::dmat3(dvec3(ca, sa, 0), dvec3(-sa, ca, 0), dvec3(0, 0, 1)) *
        glm::dmat3(dvec3(1, 0, 0), dvec3(0, std::cos(1.1), std::sin(1.1)), dvec3(0, -std::sin(1.1), std::cos(1.1)));
    const dvec3 shift(0.3, -0.2, 0.05);
    MappedYarns moved = y;
    for (dvec3& p : moved.curves.points) p = Q * p + shift;
    for (dvec3& n : moved.normals) n = Q * n;
    PlyOptions o;
    o.count = 3;
    o.yarnRadius = 0.0004;
    const Plies a = knit::makePlies(y, o), b = knit::makePlies(moved, o);
    ASSERT_EQ(a.curves.pointCount(), b.curves.pointCount());
    for (size_t i = 0; i < a.curves.pointCount(); ++i)
        EXPECT_NEAR(glm::length(Q * a.curves.points[i] + shift - b.curves.points[i]), 0.0, 1e-10) << i;
}

TEST(Plies, degenerateYarnsGiveFinitePliesInYarnMajorOrder) {
    MappedYarns y;
    const dvec3 a(0, 0, 0), b(0.002, 0, 0), c(0.002, 0.002, 0);
    addYarn(y, {a, a, b, b, c}, false);   // repeated points
    addYarn(y, {dvec3(1, 1, 1)}, false);  // one point: no plies
    addYarn(y, {a, b, a, c}, false);      // exact hairpin
    addYarn(y, {}, true);                 // empty: no plies
    addYarn(y, {a, b}, true);             // closed two-point loop
    addYarn(y, circle(0.003, 5), true);
    PlyOptions o;
    o.count = 3;
    o.yarnRadius = 0.0003;
    const Plies p = knit::makePlies(y, o);
    const std::vector<uint32_t> yarns{0, 0, 0, 2, 2, 2, 4, 4, 4, 5, 5, 5};
    EXPECT_EQ(p.yarnOfCurve, yarns);
    const MappedYarns r = resampledFor(y, o);
    ASSERT_EQ(p.curves.curveCount(), yarns.size());
    for (size_t k = 0; k < yarns.size(); ++k) {
        EXPECT_EQ(p.plyOfCurve[k], k % 3);
        EXPECT_EQ(p.curves.size(k), r.curves.size(yarns[k]));
        EXPECT_EQ(p.curves.isClosed(k), r.curves.isClosed(yarns[k]));
    }
    ASSERT_EQ(p.radial.size(), p.curves.pointCount());
    for (size_t i = 0; i < p.curves.pointCount(); ++i) {
        ASSERT_TRUE(knit::util::finite(p.curves.points[i])) << i;
        EXPECT_NEAR(glm::length(p.radial[i]), 1.0, 1e-12) << i;
    }
}

TEST(Plies, pliesIndependentOfThreadCount) {
    MappedYarns y;
    for (int k = 0; k < 40; ++k) addYarn(y, knitCurve(0.0005 + 0.00001 * k, 3, 20), k % 3 == 0);
    PlyOptions o;
    o.count = 4;
    o.yarnRadius = 0.0004;
    Plies one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = knit::makePlies(y, o);
    }
    const Plies two = knit::makePlies(y, o);
    EXPECT_TRUE(one.curves.points == two.curves.points);
    EXPECT_TRUE(one.radial == two.radial);
    EXPECT_EQ(one.curves.offsets, two.curves.offsets);
}

// The streaming export generates plies in batches of its own choosing: every split of the yarn
// list must give the curves of makePlies bit for bit (same points, radial directions, order).
TEST(Plies, generatorBatchesConcatenateToMakePlies) {
    MappedYarns y;
    for (int k = 0; k < 25; ++k) addYarn(y, knitCurve(0.0005 + 0.00002 * k, 2 + k % 3, 16), k % 4 == 0);
    addYarn(y, {dvec3(1, 1, 1)}, false);  // no plies, in the middle of a batch
    for (int k = 0; k < 5; ++k) addYarn(y, circle(0.002 + 0.0001 * k, 9), true);
    PlyOptions o;
    o.count = 3;
    o.yarnRadius = 0.0003;
    const Plies all = knit::makePlies(y, o);
    const knit::PlyGenerator gen(y, o);
    ASSERT_EQ(gen.yarnCount(), y.curves.curveCount());
    for (const size_t step : {size_t(1), size_t(4), size_t(7), size_t(31)}) {
        knit::PlyScratch scratch;
        Plies batch;
        std::vector<dvec3> points, radial;
        std::vector<uint32_t> yarnOfCurve, sizes;
        for (size_t first = 0; first < gen.yarnCount(); first += step) {
            gen.generate(first, std::min(first + step, gen.yarnCount()), batch, scratch);  // reused: cleared
            ASSERT_EQ(batch.radial.size(), batch.curves.pointCount());
            points.insert(points.end(), batch.curves.points.begin(), batch.curves.points.end());
            radial.insert(radial.end(), batch.radial.begin(), batch.radial.end());
            yarnOfCurve.insert(yarnOfCurve.end(), batch.yarnOfCurve.begin(), batch.yarnOfCurve.end());
            for (size_t c = 0; c < batch.curves.curveCount(); ++c) sizes.push_back(batch.curves.size(c));
        }
        EXPECT_TRUE(points == all.curves.points) << "batches of " << step;
        EXPECT_TRUE(radial == all.radial) << "batches of " << step;
        EXPECT_EQ(yarnOfCurve, all.yarnOfCurve) << "batches of " << step;
        ASSERT_EQ(sizes.size(), all.curves.curveCount());
        for (size_t c = 0; c < sizes.size(); ++c) EXPECT_EQ(sizes[c], all.curves.size(c)) << "curve " << c;
    }
    // The planning estimate is a lower bound of what each yarn really gets.
    for (size_t yarn = 0; yarn + 1 < gen.yarnCount(); ++yarn) {
        if (y.curves.size(yarn) < 2) continue;
        knit::PlyScratch scratch;
        Plies one;
        gen.generate(yarn, yarn + 1, one, scratch);
        EXPECT_LE(gen.estimatePoints(yarn), one.curves.pointCount()) << "yarn " << yarn;
    }
}

TEST(Plies, generatorRejectsBadYarnsBeforeGenerating) {
    MappedYarns y;
    addYarn(y, knitCurve(0.0005, 2, 16), false);
    y.curves.points[5].y = std::numeric_limits<double>::quiet_NaN();
    PlyOptions o;
    o.yarnRadius = 0.0003;
    try {
        knit::PlyGenerator gen(y, o);
        FAIL() << "expected knit::Error";
    } catch (const knit::Error& e) {
        EXPECT_NE(std::string(e.what()).find("yarn 0 point 5"), std::string::npos) << e.what();
    }
    o.samplesPerTurn = 2;
    EXPECT_THROW(knit::PlyGenerator(MappedYarns{}, o), knit::Error);
}
