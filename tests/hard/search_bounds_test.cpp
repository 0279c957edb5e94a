// Search without bound (docs/hard-cases.md, "Search radii"): absurd clamp, weld and partner
// tolerances end with a clear error or a result (a search without bound would hang: ctest's
// timeout); the partner search pairs a cell of 40000 courses (its speed: bench/core_bench.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "knit/error.hpp"
#include "knit/pattern.hpp"
#include "knit/scene.hpp"
#include "scene_refusals.hpp"

namespace {

using knit::test::errorOf;

knit::SceneOptions smallPlane() { return knit::test::smallPlaneScene(); }

TEST(SearchBounds, absurdClampToleranceIsRefusedNamingTheSetting) {
    for (double tol : {1e3, 1e12, 1e300}) {
        knit::SceneOptions o = smallPlane();
        o.bind.clampTolerance = tol;
        std::string m;
        m = errorOf([&] { knit::buildScene(o); });
        EXPECT_NE(m.find("the clamp tolerance"), std::string::npos) << m;
        EXPECT_NE(m.find("beyond one pattern period"), std::string::npos) << m;
    }
}

TEST(SearchBounds, absurdWeldToleranceIsRefusedUnlessWeldingIsOff) {
    knit::SceneOptions o = smallPlane();
    o.bind.weldTolerance = 1e200;
    EXPECT_NE(errorOf([&] { knit::buildScene(o); }).find("the weld tolerance"), std::string::npos);
    o.bind.weld = false;
    EXPECT_EQ(errorOf([&] { knit::buildScene(o); }), "");
}

TEST(SearchBounds, clampToleranceWithinOnePeriodStillClamps) {
    knit::SceneOptions o = smallPlane();
    o.bind.clampTolerance = 5;  // below the period (~6.6 yarn radii here)
    EXPECT_EQ(errorOf([&] { knit::buildScene(o); }), "");
}

// 40000 short courses in one curves cell: the all-pairs partner search took minutes (80000 ends,
// 2.6e10 distance tests); the grid finds the same pairs in well under a second. Its speed is
// measured by BM_PartnerSearch (bench/core_bench.cpp, with its complexity fit); here the pairs.
TEST(SearchBounds, partnerSearchOnABigCurvesCellPairsEveryCourse) {
    knit::CurveCell cell;
    cell.name = "big.json";
    const int courses = 40000;
    cell.px = 0.01;
    cell.py = 0.01 * courses;
    cell.radius = 0.001;
    for (int c = 0; c < courses; ++c) {
        const double y = 0.01 * c + 0.005;
        cell.curves.push_back({{0.001, y, 0}, {0.005, y, 0}, {0.009, y, 0}});
    }
    knit::Pattern p;
    p = knit::patternFromCurves(cell);
    EXPECT_EQ(p.edges.size(), size_t(courses) * 3);  // two in-cell edges + one periodic edge per course
}

// 40000 curves packed into a 1 cm cell (ends 2.5e-7 m apart, segments 4 mm long): every end was a
// candidate partner of every other, 6.4e9 pairs, std::bad_alloc after 3 GB. Refused before the
// pairs are listed (0.5 s here), naming the file and why.
TEST(SearchBounds, curvesPackedCloserThanTheirSegmentsAreRefusedBeforeListingEveryPair) {
    knit::CurveCell cell;
    cell.name = "dense.json";
    const int courses = 40000;
    cell.px = cell.py = 0.01;
    cell.radius = 0.01 / courses / 4;
    for (int c = 0; c < courses; ++c) {
        const double y = 0.01 * (c + 0.5) / courses;
        cell.curves.push_back({{0.001, y, 0}, {0.005, y, 0}, {0.009, y, 0}});
    }
    std::string m;
    m = errorOf([&] { knit::patternFromCurves(cell); });
    EXPECT_NE(m.find("dense.json: 40000 curves whose ends lie so close together"), std::string::npos) << m;
    EXPECT_NE(m.find("split the curves into shorter segments, or give the cell fewer curves"), std::string::npos) << m;
}

TEST(SearchBounds, absurdPartnerToleranceStillPairsNeighbours) {
    knit::CurveCell cell;
    cell.name = "c.json";
    cell.px = cell.py = 0.01;
    cell.radius = 0.001;
    cell.curves.push_back({{0.001, 0.005, 0}, {0.009, 0.005, 0}});
    knit::PartnerOptions o;
    o.tolerance = 1e300;
    const knit::Pattern p = knit::patternFromCurves(cell, o);
    ASSERT_EQ(p.edges.size(), 2u);
    EXPECT_EQ(std::abs(p.edges[1].dx), 1);
}

}  // namespace
