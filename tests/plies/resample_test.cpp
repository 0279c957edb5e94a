// Tests for resampleYarns (centripetal Catmull-Rom resampling).
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "knit/error.hpp"
#include "knit/resample.hpp"
#include "plies/plies_curves.hpp"
#include "plies/resample_curve.hpp"
#include "util/checks.hpp"

using glm::dvec3;
using knit::MappedYarns;
using knit::ResampleOptions;

namespace {

using knit::test::addYarn;
using knit::test::circle;

// A wiggly 3D curve with a hairpin (exact reversal) and a tight turn in it.
std::vector<dvec3> wigglyWithHairpin() {
    std::vector<dvec3> p;
    for (int i = 0; i < 20; ++i) {
        const double t = 0.3 * i;
        p.emplace_back(0.001 * t, 0.0005 * std::sin(3 * t), 0.0003 * std::cos(5 * t));
    }
    const dvec3 tip = p.back() + dvec3(0.001, 0, 0);
    p.push_back(tip);
    p.push_back(tip - dvec3(0.001, 0, 0));  // back onto the previous point: hairpin
    p.push_back(tip - dvec3(0.002, 0.0001, 0.0));
    p.push_back(tip - dvec3(0.0021, 0.0009, 0.0001));  // tight turn
    p.push_back(tip - dvec3(0.001, 0.001, 0.0002));
    return p;
}

double maxSegment(const knit::Polylines& c, size_t k) {
    double m = 0.0;
    const uint32_t n = c.size(k);
    for (uint32_t s = 0; s < c.segmentCount(k); ++s) {
        const dvec3 a = c.points[c.begin(k) + s];
        const dvec3 b = c.points[c.begin(k) + (s + 1) % n];
        m = std::max(m, glm::length(b - a));
    }
    return m;
}

}  // namespace

TEST(Resample, resamplingKeepsOriginalVertices) {
    MappedYarns y;
    addYarn(y, wigglyWithHairpin(), false);
    addYarn(y, circle(0.004, 7), true);
    ResampleOptions o;
    o.spacing = 0.0002;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.curveCount(), 2u);
    EXPECT_FALSE(r.curves.isClosed(0));
    EXPECT_TRUE(r.curves.isClosed(1));
    for (size_t c = 0; c < 2; ++c) {
        // Every input vertex appears bit-for-bit, in order; the first and last stay at the ends.
        uint32_t j = r.curves.begin(c);
        for (uint32_t i = y.curves.begin(c); i < y.curves.end(c); ++i) {
            while (j < r.curves.end(c) && r.curves.points[j] != y.curves.points[i]) ++j;
            ASSERT_LT(j, r.curves.end(c)) << "curve " << c << " lost input vertex " << i;
        }
        EXPECT_EQ(r.curves.points[r.curves.begin(c)], y.curves.points[y.curves.begin(c)]);
        EXPECT_GT(r.curves.size(c), y.curves.size(c));  // points were inserted
    }
    EXPECT_EQ(r.curves.points[r.curves.end(0) - 1], y.curves.points[y.curves.end(0) - 1]);
}

TEST(Resample, resampleMaxSegmentBelowSpacing) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.003, 0.003);
    MappedYarns y;
    for (int c = 0; c < 20; ++c) {
        std::vector<dvec3> p;
        const int n = 2 + c;  // includes 2-point curves and random hairpins/kinks
        for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng), u(rng));
        addYarn(y, p, c % 2 == 1);
    }
    addYarn(y, wigglyWithHairpin(), false);
    addYarn(y, wigglyWithHairpin(), true);
    for (double spacing : {0.0001, 0.00037, 0.002}) {
        ResampleOptions o;
        o.spacing = spacing;
        const MappedYarns r = knit::resampleYarns(y, o);
        ASSERT_EQ(r.curves.curveCount(), y.curves.curveCount());
        for (size_t c = 0; c < r.curves.curveCount(); ++c) {
            EXPECT_LE(maxSegment(r.curves, c), spacing) << "curve " << c;
            EXPECT_GE(r.curves.size(c), y.curves.size(c));
        }
    }
}

TEST(Resample, resampledCircleStaysOnCircle) {
    // A coarse 12-gon: linear interpolation would sag by 1 - cos(15 deg) = 3.4% at the segment
    // middles; the centripetal Catmull-Rom spline stays within 0.5% of the radius.
    MappedYarns y;
    addYarn(y, circle(0.01, 12), true);
    ResampleOptions o;
    o.spacing = 0.0005;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_GT(r.curves.pointCount(), 120u);
    for (const dvec3& p : r.curves.points) EXPECT_NEAR(glm::length(p), 0.01, 0.00005);
}

TEST(Resample, twoPointCurveStaysStraightAndEven) {
    MappedYarns y;
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.0095, 0.0, 0.0)}, false);
    ResampleOptions o;
    o.spacing = 0.001;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.size(0), 11u);  // the fewest segments that fit, evenly spaced
    for (uint32_t i = 0; i < r.curves.size(0); ++i) {
        EXPECT_NEAR(r.curves.points[i].x, 0.00095 * i, 1e-15);
        EXPECT_EQ(r.curves.points[i].y, 0.0);
        EXPECT_EQ(r.curves.points[i].z, 0.0);
    }
}

TEST(Resample, repeatedPointsAreDropped) {
    MappedYarns y;
    const dvec3 a(0, 0, 0), b(0.001, 0, 0), c(0.001, 0.001, 0);
    // Exact and near-exact repeats (1e-18 m << 1e-12 * spacing); closed curve repeats its start.
    addYarn(y, {a, a, b, b + dvec3(1e-18, 0, 0), b, c, c, a}, true);
    addYarn(y, {a, a, a}, false);  // collapses to one point
    ResampleOptions o;
    o.spacing = 0.01;  // no insertion: only the merging is visible
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.curveCount(), 2u);
    ASSERT_EQ(r.curves.size(0), 3u);
    EXPECT_EQ(r.curves.points[0], a);
    EXPECT_EQ(r.curves.points[1], b);
    EXPECT_EQ(r.curves.points[2], c);
    EXPECT_TRUE(r.curves.isClosed(0));
    EXPECT_EQ(r.curves.size(1), 1u);  // single-point curves are kept (curve indices stay 1:1)
    for (const dvec3& p : r.curves.points) EXPECT_TRUE(knit::util::finite(p));
}

TEST(Resample, singlePointAndEmptyCurvesKeepCurveIndices) {
    MappedYarns y;
    addYarn(y, {}, false);
    addYarn(y, {dvec3(1, 2, 3)}, false);
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.003, 0, 0)}, false);
    ResampleOptions o;
    o.spacing = 0.001;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.curveCount(), 3u);
    EXPECT_EQ(r.curves.size(0), 0u);
    ASSERT_EQ(r.curves.size(1), 1u);
    EXPECT_EQ(r.curves.points[r.curves.begin(1)], dvec3(1, 2, 3));
    EXPECT_EQ(r.curves.size(2), 4u);
    EXPECT_EQ(r.normals.size(), r.curves.pointCount());
}

TEST(Resample, closedTwoPointCurveIsFinite) {
    MappedYarns y;
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.004, 0, 0)}, true);
    ResampleOptions o;
    o.spacing = 0.001;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_TRUE(r.curves.isClosed(0));
    EXPECT_LE(maxSegment(r.curves, 0), 0.001);
    EXPECT_GE(r.curves.size(0), 8u);  // both directions of the back-and-forth loop get points
    for (const dvec3& p : r.curves.points) {
        EXPECT_TRUE(knit::util::finite(p));
        EXPECT_NEAR(p.y, 0.0, 1e-15);  // the degenerate loop stays on its segment
        EXPECT_GE(p.x, -1e-15);
        EXPECT_LE(p.x, 0.004 + 1e-15);
    }
}

TEST(Resample, normalsInterpolateLinearlyAndRenormalize) {
    MappedYarns y;
    const std::vector<dvec3> pts{dvec3(0, 0, 0), dvec3(0.002, 0, 0)};
    y.curves.addCurve(pts.data(), pts.size(), false);
    y.normals = {dvec3(0, 0, 1), dvec3(0, 1, 0)};
    ResampleOptions o;
    o.spacing = 0.001;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.size(0), 3u);
    EXPECT_EQ(r.normals[0], dvec3(0, 0, 1));
    EXPECT_EQ(r.normals[2], dvec3(0, 1, 0));
    const dvec3 mid = glm::normalize(dvec3(0, 1, 1));
    EXPECT_NEAR(glm::length(r.normals[1] - mid), 0.0, 1e-12);
}

TEST(Resample, invalidResampleInputRejected) {
    MappedYarns y;
    addYarn(y, {dvec3(0, 0, 0), dvec3(1, 0, 0)}, false);
    ResampleOptions o;
    o.spacing = 0.0;
    EXPECT_THROW(knit::resampleYarns(y, o), knit::Error);
    o.spacing = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(knit::resampleYarns(y, o), knit::Error);
    o.spacing = 0.1;
    MappedYarns bad = y;
    bad.curves.points[1].y = std::numeric_limits<double>::infinity();
    try {
        knit::resampleYarns(bad, o);
        FAIL() << "non-finite point accepted";
    } catch (const knit::Error& e) {
        EXPECT_NE(std::string(e.what()).find("yarn 0 point 1"), std::string::npos) << e.what();
    }
    MappedYarns wrongNormals = y;
    wrongNormals.normals.pop_back();
    EXPECT_THROW(knit::resampleYarns(wrongNormals, o), knit::Error);
    MappedYarns broken = y;
    broken.curves.offsets = {0, 5};  // offsets past the points
    EXPECT_THROW(knit::resampleYarns(broken, o), knit::Error);
    // An absurd spacing is refused before anything is allocated (would be 1e12 points).
    ResampleOptions tiny;
    tiny.spacing = 1e-12;
    try {
        knit::resampleYarns(y, tiny);
        FAIL() << "huge output accepted";
    } catch (const knit::Error& e) {
        EXPECT_NE(std::string(e.what()).find("spacing"), std::string::npos) << e.what();
    }
    MappedYarns noNormals = y;
    noNormals.normals.clear();  // allowed: no normals in, none out
    EXPECT_TRUE(knit::resampleYarns(noNormals, o).normals.empty());
}

TEST(Resample, nearRepeatedPointsAboveMergeDistanceStayBounded) {
    // Points 1e-10 * spacing apart are not merged; the centripetal knots (|d|^(1/2)) keep the
    // spline bounded next to them (no overshoot, no NaN).
    const double spacing = 0.0004;
    MappedYarns y;
    const dvec3 a(0, 0, 0), b(0.002, 0.001, 0), c(0.004, 0, 0.001);
    addYarn(y, {a, b, b + dvec3(1e-10 * spacing, 0, 0), c, dvec3(0.006, 0.001, 0)}, false);
    ResampleOptions o;
    o.spacing = spacing;
    const MappedYarns r = knit::resampleYarns(y, o);
    ASSERT_EQ(r.curves.curveCount(), 1u);
    EXPECT_LE(maxSegment(r.curves, 0), spacing);
    for (const dvec3& p : r.curves.points) {
        ASSERT_TRUE(knit::util::finite(p));
        EXPECT_GE(p.x, -1e-9);
        EXPECT_LE(p.x, 0.006 + 1e-9);
        EXPECT_LE(std::abs(p.y), 0.0015);  // stays near the control polygon's extent
    }
    for (const dvec3& n : r.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
}

// Replaying a curve's layout on the pose it was recorded on gives resampleCurve's points bit for
// bit: the replay reads its divisions from per-segment reciprocal tables (knot intervals and
// reciprocals four at a time in AVX2 when the CPU has it), resampleCurve computes them one by one
// per piece, so this pins the tables' indexing (both ends of open curves, the wrap of closed
// ones, merged repeated points) and the AVX2 lanes to the very same values.
TEST(Resample, layoutReplayOnTheRecordingPoseIsResampleCurveBitForBit) {
    MappedYarns y;
    addYarn(y, wigglyWithHairpin(), false);
    addYarn(y, circle(0.003, 11), true);
    std::vector<dvec3> repeated = wigglyWithHairpin();
    repeated.insert(repeated.begin() + 7, repeated[6]);  // merged when resampled
    addYarn(y, repeated, true);
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.003, 0.001, 0)}, false);
    addYarn(y, {dvec3(0, 0, 0), dvec3(0.003, 0.001, 0), dvec3(0.001, 0.003, 0.002)}, true);
    for (size_t c = 0; c < y.curves.curveCount(); ++c) {
        knit::ResampleScratch scratch;
        knit::ResampleLayout layout;
        std::vector<dvec3> recorded;
        const size_t count = knit::resampleCurve(y, c, 0.0004, recorded, nullptr, scratch, &layout);
        ASSERT_GT(count, layout.kept.size()) << "curve " << c;  // points were inserted
        std::vector<dvec3> replayed(count + 1, dvec3(-1.0));
        EXPECT_EQ(knit::resampleCurveWithLayout(y.curves, c, layout.kept.data(), layout.kept.size(),
                                                layout.pieces.data(), replayed.data(), scratch),
                  count);
        EXPECT_EQ(std::memcmp(replayed.data(), recorded.data(), count * sizeof(dvec3)), 0) << "curve " << c;
        EXPECT_EQ(replayed[count], dvec3(-1.0)) << "curve " << c;
    }
}
