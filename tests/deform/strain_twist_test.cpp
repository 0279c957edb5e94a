// The twist column of a strain table (dtwist) turns the plies about their yarn by that angle,
// when the scene's plies are built and when an Animator evaluates them; zero strain leaves them
// bit for bit as without the table.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "common/fixtures.hpp"
#include "common/ply_runs.hpp"
#include "knit/animation.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

using glm::dvec3;

constexpr double kTwist = 0.6;  // radians

// No displacement; the twist is 0 up to sx = 0 and kTwist from sx = 0.1 on, whatever sa and sy.
std::shared_ptr<const StrainTable> twistTable() {
    auto t = std::make_shared<StrainTable>();
    t->source = "twist.npy";
    t->axes = {std::vector<double>{-0.2, 0.0, 0.1, 1.0}, std::vector<double>{-0.7, 0.7},
               std::vector<double>{-0.2, 1.0}};
    t->vertexCount = generateStockinette().points.size();
    const size_t nx = 4, na = 2, ny = 2;
    t->data.assign(4 * t->vertexCount * nx * na * ny, 0.0F);
    for (size_t row = 0; row < t->data.size() / 4; ++row) t->data[4 * row + 3] = row % nx >= 2 ? float(kTwist) : 0.0F;
    return t;
}

// The plane at the pattern's own shape (isometric) or stretched by 1.4 along the courses against
// the rows (strain sx = 0.18, sy = -0.15 at the placement's scale).
// With `detail`: the scene of a view (its plies cut from whole yarns by piecePlies).
Scene planeScene(const std::shared_ptr<const StrainTable>& table, bool stretched,
                 const std::optional<DetailOptions>& detail = std::nullopt) {
    const Pattern p = generateStockinette();
    SceneOptions o;
    o.detail = detail;
    o.placement.repeats = {0.05 / ((stretched ? 1.4 : 1.0) * p.px), 0.05 / p.py};
    o.deform.mode = table ? DeformMode::Strain : DeformMode::None;
    o.deform.table = table;
    return buildScene(p, test::planeMesh(test::Triangulation::Regular, 8, 0.05), o);
}

// Per ply point, the signed angle from `a`'s radial direction to `b`'s about the yarn (the
// direction of the ply curve's centre line); the smallest and largest over all points.
std::pair<double, double> turn(const Plies& a, const Plies& b) {
    EXPECT_EQ(a.curves.offsets, b.curves.offsets);
    double lo = 1e9, hi = -1e9;
    for (size_t c = 0; c < a.curves.curveCount(); ++c)
        for (uint32_t i = a.curves.begin(c); i + 1 < a.curves.end(c); ++i) {
            const dvec3 centre0 = a.curves.points[i] - a.centerRadius * a.radial[i];
            const dvec3 centre1 = a.curves.points[i + 1] - a.centerRadius * a.radial[i + 1];
            const dvec3 t = glm::normalize(centre1 - centre0);
            const dvec3 ra = a.radial[i], rb = b.radial[i];
            const double angle = std::atan2(glm::dot(glm::cross(ra, rb), t), glm::dot(ra, rb));
            lo = std::min(lo, angle);
            hi = std::max(hi, angle);
        }
    return {lo, hi};
}

Plies animatedPlies(const Scene& s) {
    AnimatorOptions o;
    o.plies = true;
    o.radial = true;
    const Animator a(s, o);
    AnimationFrame f;
    a.evaluate(s.mesh().positions, f);
    return f.plies;
}

TEST(StrainTwist, aTableTwistTurnsThePliesByItsAngle) {
    const Scene none = planeScene(nullptr, true), strain = planeScene(twistTable(), true);
    // No displacement in the table: the same yarns, bit for bit.
    ASSERT_EQ(none.yarns().curves.points, strain.yarns().curves.points);
    ASSERT_EQ(strain.yarns().twist.size(), strain.yarns().curves.points.size());
    ASSERT_GT(strain.plies().curves.pointCount(), 1000U);
    // Built plies: turned about their yarn by the table's twist (the plies' phase, towards B = T x N).
    const auto [lo, hi] = turn(none.plies(), strain.plies());
    EXPECT_NEAR(lo, kTwist, 0.02);
    EXPECT_NEAR(hi, kTwist, 0.02);
    // The Animator's plies on the rest pose (knit animate, Python's evaluate_plies): the same turn.
    const auto [alo, ahi] = turn(animatedPlies(none), animatedPlies(strain));
    EXPECT_NEAR(alo, kTwist, 0.02);
    EXPECT_NEAR(ahi, kTwist, 0.02);
}

// The twist is made for the plies only: an Animator of the yarns alone leaves it empty (and does
// not pay for it), one with plies gets the table's twist per yarn vertex.
TEST(StrainTwist, onlyAnAnimatorWithPliesGetsTheTwist) {
    const Scene strain = planeScene(twistTable(), true);
    for (const bool plies : {false, true}) {
        AnimatorOptions o;
        o.plies = plies;
        o.stats = false;
        const Animator a(strain, o);
        AnimationFrame f;
        a.evaluate(strain.mesh().positions, f);
        if (!plies) {
            EXPECT_TRUE(f.yarns.twist.empty());
            continue;
        }
        ASSERT_EQ(f.yarns.twist.size(), f.yarns.curves.points.size());
        EXPECT_EQ(f.yarns.twist, strain.yarns().twist);  // the rest pose: the scene's own twist
        EXPECT_GT(*std::max_element(f.yarns.twist.begin(), f.yarns.twist.end()), 0.9 * kTwist);
    }
}

TEST(StrainTwist, zeroStrainLeavesThePliesBitForBit) {
    const Scene none = planeScene(nullptr, false), strain = planeScene(twistTable(), false);
    const auto& a = none.plies().curves.points;
    const auto& b = strain.plies().curves.points;
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 1000U);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])), 0);
    const Plies an = animatedPlies(none), as = animatedPlies(strain);
    ASSERT_EQ(an.curves.points.size(), as.curves.points.size());
    EXPECT_EQ(std::memcmp(an.curves.points.data(), as.curves.points.data(), an.curves.points.size() * sizeof(dvec3)),
              0);
}

// A close-up view's plies (knit render, export of a view) are the full scene's plies where drawn,
// the table's twist included: a view of part of the strained plane, every drawn cell at the ply
// level, yarns of the whole mesh (so yarn numbers match the full scene's).
TEST(StrainTwist, aViewsPliesAreTheFullScenesPliesWithTheTwist) {
    DetailOptions d;
    d.yarnLevel = false;
    d.region = false;
    d.cullBackFaces = false;
    View v;
    v.eye = {0.0125, 0.0125, 0.03};  // over one quarter of the 5 cm plane, looking down
    v.target = {0.0125, 0.0125, 0.0};
    v.up = {0.0, 1.0, 0.0};
    d.view = v;
    const Scene full = planeScene(twistTable(), true), view = planeScene(twistTable(), true, d);
    ASSERT_TRUE(view.detail().has_value());
    ASSERT_EQ(full.yarns().curves.points, view.yarns().curves.points);
    const Plies& whole = full.plies();
    const Plies& cut = view.plies();
    ASSERT_GT(cut.curves.curveCount(), 10U);
    const size_t partial = test::expectEveryCurveIsARunOfTheFullPly(whole, cut);
    EXPECT_GT(partial, 0U);  // the view cuts yarns, not only whole ones
    EXPECT_LT(cut.curves.pointCount(), whole.curves.pointCount());
}

}  // namespace
}  // namespace knit
