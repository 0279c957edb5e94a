// animation_stats: the closest approach of different yarns against brute force, over a sequence
// of frames that reuses one scratch (the search starts from the previous frame's closest pair).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "knit/animation.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

using glm::dvec3;

constexpr double kRadius = 0.001;  // yarn radius: diameters are 2 mm

// Centrelines with their rest arc lengths and rest lengths (what the Animator passes), and the
// yarn of each point for the brute force (the search takes it from the curves' offsets).
struct Centres {
    Polylines curves;
    std::vector<uint32_t> yarnOf;
    std::vector<double> arc, length;
};

// `yarns` random walks of `points` steps of half a radius in a 2 cm box, every third closed.
Centres randomYarns(int yarns, int points, std::mt19937& rng) {
    std::uniform_real_distribution<double> box(0.0, 0.02), unit(-1.0, 1.0);
    Centres c;
    for (int y = 0; y < yarns; ++y) {
        dvec3 p(box(rng), box(rng), box(rng));
        double s = 0;
        for (int k = 0; k < points; ++k) {
            c.curves.points.push_back(p);
            c.yarnOf.push_back(static_cast<uint32_t>(y));
            c.arc.push_back(s);
            dvec3 step(unit(rng), unit(rng), unit(rng));
            step = 0.5 * kRadius * glm::normalize(step + dvec3(0.8, 0, 0));
            p += step;
            s += glm::length(step);
        }
        c.length.push_back(s);
        c.curves.offsets.push_back(static_cast<uint32_t>(c.curves.points.size()));
        c.curves.closed.push_back(y % 3 == 0 ? 1 : 0);
    }
    return c;
}

// Every pair, in yarn diameters (+infinity beyond the cutoff), by the documented rule.
double bruteForce(const Centres& c, const AnimatorOptions& o) {
    const double d = 2 * kRadius, sep = o.sameYarnSeparation * d;
    double best = std::numeric_limits<double>::infinity();
    const std::vector<dvec3>& p = c.curves.points;
    for (size_t i = 0; i < p.size(); ++i)
        for (size_t j = i + 1; j < p.size(); ++j) {
            const uint32_t y = c.yarnOf[i];
            if (y == c.yarnOf[j]) {
                double along = std::abs(c.arc[i] - c.arc[j]);
                if (c.curves.isClosed(y)) along = std::min(along, c.length[y] - along);
                if (along <= sep) continue;
            }
            best = std::min(best, glm::length(p[i] - p[j]));
        }
    return best < o.distanceCutoff * d ? best / d : std::numeric_limits<double>::infinity();
}

double search(const Centres& c, const AnimatorOptions& o, DistanceScratch& scratch) {
    return minYarnDistance(c.curves, c.arc, c.length, kRadius, o, scratch);
}

void expectSame(double found, double expected, int frame) {
    if (std::isinf(expected)) {
        EXPECT_TRUE(std::isinf(found)) << "frame " << frame << ": found " << found;
        return;
    }
    EXPECT_NEAR(found, expected, 1e-6) << "frame " << frame;
}

// Frames that jitter, pull the closest pair apart (the previous pair's bound is then loose) and
// bring a far yarn in (a new closest pair the previous frame did not have).
TEST(AnimationStats, closestApproachEqualsBruteForceFrameAfterFrame) {
    std::mt19937 rng(7);
    Centres c = randomYarns(12, 60, rng);
    const AnimatorOptions o;
    DistanceScratch scratch;
    std::normal_distribution<double> jitter(0.0, 0.1 * kRadius);
    for (int frame = 0; frame < 8; ++frame) {
        if (frame % 3 == 1)
            for (dvec3& q : c.curves.points) q += dvec3(jitter(rng), jitter(rng), jitter(rng));
        if (frame == 2 || frame == 5) {  // move the yarn of the closest pair far away
            ASSERT_TRUE(scratch.hasPair);
            const uint32_t y = c.yarnOf[scratch.pair[0]];
            for (uint32_t k = c.curves.begin(y); k < c.curves.end(y); ++k) c.curves.points[k].z += 0.05;
        }
        if (frame == 4) {  // a far yarn pressed onto another, closer than anything before
            const uint32_t a = c.curves.begin(3), b = c.curves.begin(4) + 20;
            const dvec3 shift = c.curves.points[b] - c.curves.points[a] + dvec3(0.05 * kRadius, 0, 0);
            for (uint32_t k = c.curves.begin(3); k < c.curves.end(3); ++k) c.curves.points[k] += shift;
        }
        expectSame(search(c, o, scratch), bruteForce(c, o), frame);
    }
}

TEST(AnimationStats, nothingWithinTheCutoffIsInfinityAndTheNextFrameStillFindsPairs) {
    // Two straight open yarns along x, 1 m apart, then 1.5 mm apart.
    Centres c;
    for (int y = 0; y < 2; ++y) {
        for (int k = 0; k < 40; ++k) {
            c.curves.points.push_back(dvec3(0.5 * kRadius * k, 0, y * 0.0015));
            c.yarnOf.push_back(static_cast<uint32_t>(y));
            c.arc.push_back(0.5 * kRadius * k);
        }
        c.length.push_back(0.5 * kRadius * 39);
        c.curves.offsets.push_back(static_cast<uint32_t>(c.curves.points.size()));
        c.curves.closed.push_back(0);
    }
    for (uint32_t k = c.curves.begin(1); k < c.curves.end(1); ++k) c.curves.points[k].z += 1.0;
    const AnimatorOptions o;
    DistanceScratch scratch;
    EXPECT_TRUE(std::isinf(search(c, o, scratch)));
    EXPECT_TRUE(std::isinf(bruteForce(c, o)));
    for (uint32_t k = c.curves.begin(1); k < c.curves.end(1); ++k) c.curves.points[k].z -= 1.0;
    expectSame(search(c, o, scratch), 0.75, 1);
}

// The search finds each point's yarn by walking the curve offsets: with empty yarns between and
// over many parallel ranges (more than 2 x 16384 points), every point must get its own yarn, else
// two neighbours of one yarn (a quarter of a diameter apart) would count as different yarns.
TEST(AnimationStats, eachPointsYarnComesFromTheOffsetsAcrossRangesAndEmptyYarns) {
    Centres c;
    const int yarns = 40, points = 1200;
    for (int y = 0; y < yarns; ++y) {
        if (y % 5 == 2) {  // an empty yarn
            c.length.push_back(0.0);
            c.curves.offsets.push_back(static_cast<uint32_t>(c.curves.points.size()));
            c.curves.closed.push_back(0);
            continue;
        }
        for (int k = 0; k < points; ++k) {  // straight along x, 1.5 mm apart in z
            c.curves.points.push_back(dvec3(0.5 * kRadius * k, 0, y * 0.0015));
            c.arc.push_back(0.5 * kRadius * k);
        }
        c.length.push_back(0.5 * kRadius * (points - 1));
        c.curves.offsets.push_back(static_cast<uint32_t>(c.curves.points.size()));
        c.curves.closed.push_back(0);
    }
    ASSERT_GT(c.curves.pointCount(), 2u * 16384u);
    const AnimatorOptions o;
    DistanceScratch scratch;
    expectSame(search(c, o, scratch), 0.75, 0);
}

// One closed yarn: its neighbouring points never count, a hairpin pressed onto itself does
// (the other side is farther along the yarn than the separation, the short way round).
TEST(AnimationStats, aLoopCountsOnlyWhereItIsPressedOntoItself) {
    Centres c;
    const int n = 400;
    const double ring = 0.02;  // circumference 2 pi 2 cm, spacing ~0.3 mm
    for (int k = 0; k < n; ++k) {
        const double t = 2 * knit::util::kPi * k / n;
        c.curves.points.push_back(dvec3(ring * std::cos(t), ring * std::sin(t), 0));
        c.arc.push_back(ring * t);
        c.yarnOf.push_back(0);
    }
    c.length.push_back(2 * knit::util::kPi * ring);
    c.curves.offsets.push_back(n);
    c.curves.closed.push_back(1);
    const AnimatorOptions o;
    DistanceScratch scratch;
    EXPECT_TRUE(std::isinf(search(c, o, scratch)));  // the ring's diameter is 20 yarn diameters
    // Squash the ring flat to a 1.5 mm gap: its two sides now face each other (closest near
    // the ends, where they are still far enough apart along the yarn).
    for (dvec3& q : c.curves.points) q.y *= 0.0015 / (2 * ring);
    const double found = search(c, o, scratch);
    expectSame(found, bruteForce(c, o), 1);
    EXPECT_LT(found, 0.75);
}

}  // namespace
}  // namespace knit
