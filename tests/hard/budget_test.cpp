// Size budget (docs/hard-cases.md, "Size budget"): each big stage estimates its memory from its
// counts and refuses before allocating, naming the option that drives it; --max-memory sizes.
#include <gtest/gtest.h>

#include <string>

#include "knit/budget.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"
#include "scene_refusals.hpp"

namespace {

using knit::MemoryBudget;

using knit::test::errorOf;

knit::SceneOptions smallPlane() { return knit::test::smallPlaneScene(); }

TEST(Budget, defaultIsAtMostFourGiB) {
    EXPECT_LE(MemoryBudget().bytes(), uint64_t(4) << 30);
    EXPECT_GT(MemoryBudget().bytes(), uint64_t(0));
}

TEST(Budget, sizesWithUnitsParse) {
    EXPECT_EQ(knit::parseMemorySize("8G"), uint64_t(8) << 30);
    EXPECT_EQ(knit::parseMemorySize("512M"), uint64_t(512) << 20);
    EXPECT_EQ(knit::parseMemorySize("64k"), uint64_t(64) << 10);
    EXPECT_EQ(knit::parseMemorySize("1.5GiB"), uint64_t(3) << 29);
    EXPECT_EQ(knit::parseMemorySize("4096"), 4096u);
    EXPECT_EQ(knit::parseMemorySize("2T"), uint64_t(2) << 40);
}

TEST(Budget, malformedSizesNameTheOption) {
    for (const char* bad : {"", "G", "8X", "-1G", "0", "nan", "inf", "1e30T", "8 G", "8GG"})
        EXPECT_NE(errorOf([&] { knit::parseMemorySize(bad); }).find("--max-memory"), std::string::npos) << bad;
}

TEST(Budget, refusalNamesEstimateWhatAndOption) {
    const std::string m =
        errorOf([] { MemoryBudget(uint64_t(1) << 30).require(3.0 * (uint64_t(1) << 30), "7 things", "--knob"); });
    EXPECT_EQ(m, "needs about 3 GiB (estimate) for 7 things, over the memory budget of 1 GiB; lower --knob or raise "
                 "--max-memory");
    EXPECT_EQ(errorOf([] { MemoryBudget(100).require(100, "x", "y"); }), "");
}

TEST(Budget, manyCellsFromRepeatsAreRefusedBeforeTheGrid) {
    knit::SceneOptions o = smallPlane();
    o.placement.repeats = {3000, 3000};
    o.budget = MemoryBudget(uint64_t(64) << 20);
    const std::string m = errorOf([&] { knit::buildScene(o); });
    EXPECT_NE(m.find("pattern cells"), std::string::npos) << m;
    EXPECT_NE(m.find("lower --repeats"), std::string::npos) << m;
}

TEST(Budget, tinyPlyPitchIsRefusedNamingSamplesAndPitch) {
    knit::SceneOptions o = smallPlane();
    o.plies.pitch = 1e-7;
    const std::string m = errorOf([&] { knit::buildScene(o); });
    EXPECT_NE(m.find("ply vertices"), std::string::npos) << m;
    EXPECT_NE(m.find("--ply-pitch"), std::string::npos) << m;
}

TEST(Budget, patternVertexFarOutsideItsCellIsRefusedNamingIt) {
    knit::Pattern p = knit::builtinPattern("stockinette");
    p.name = "far.pyp";
    p.points[0].x += 20000 * p.px;  // one vertex 20000 periods away: a tile reaches 2e4 x 1 cells
    knit::SceneOptions o = smallPlane();
    o.placement.repeats = {100, 100};
    o.budget = MemoryBudget(uint64_t(16) << 20);
    const std::string m = errorOf([&] { knit::buildScene(p, knit::makePlane(o.meshOptions), o); });
    EXPECT_NE(m.find("far outside its cell (in far.pyp)"), std::string::npos) << m;
}

TEST(Budget, sceneWithinTheBudgetIsBuiltUnchanged) {
    const knit::Scene s = knit::buildScene(smallPlane());
    EXPECT_GT(s.yarns().curves.pointCount(), 0u);
}

}  // namespace
