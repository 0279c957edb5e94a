// Size budget (docs/hard-cases.md, "Size budget"): each big stage estimates its memory from its
// counts and refuses before allocating, naming the option that drives it; --max-memory sizes.
#include <gtest/gtest.h>

#include <string>

#include <filesystem>

#include "knit/budget.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "scene_refusals.hpp"
#include "test_util.hpp"
#ifdef KNIT_HARD_HAVE_RENDER_CHECK
#include "knit/render.hpp"
#endif

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

TEST(Budget, malformedSizesNameTheSetting) {
    for (const char* bad : {"", "G", "8X", "-1G", "0", "nan", "inf", "1e30T", "8 G", "8GG"})
        EXPECT_NE(errorOf([&] { knit::parseMemorySize(bad); }).find("the memory budget '"), std::string::npos) << bad;
}

TEST(Budget, refusalNamesEstimateWhatAndOption) {
    const std::string m =
        errorOf([] { MemoryBudget(uint64_t(1) << 30).require(3.0 * (uint64_t(1) << 30), "7 things", "the knob"); });
    EXPECT_EQ(m, "needs about 3 GiB (estimate) for 7 things, over the memory budget of 1 GiB; lower the knob or raise "
                 "the memory budget");
    EXPECT_EQ(errorOf([] { MemoryBudget(100).require(100, "x", "y"); }), "");
}

TEST(Budget, manyCellsFromRepeatsAreRefusedBeforeTheGrid) {
    knit::SceneOptions o = smallPlane();
    o.placement.repeats = {3000, 3000};
    o.budget = MemoryBudget(uint64_t(64) << 20);
    const std::string m = errorOf([&] { knit::buildScene(o); });
    EXPECT_NE(m.find("pattern cells"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the repeats"), std::string::npos) << m;
}

TEST(Budget, tinyPlyPitchIsRefusedNamingSamplesAndPitch) {
    knit::SceneOptions o = smallPlane();
    o.plies.pitch = 1e-7;
    const std::string m = errorOf([&] { knit::buildScene(o); });
    EXPECT_NE(m.find("ply vertices"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the samples per turn, or raise the ply pitch,"), std::string::npos) << m;
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

TEST(Budget, generatorSampleCountIsRefusedNamingSamples) {
    knit::StockinetteParams p;
    p.samplesPerStitch = 1000000;  // 1e6 samples x 96 B = 92 MiB
    p.budget = MemoryBudget(uint64_t(16) << 20);
    const std::string m = errorOf([&] { knit::generateStockinette(p); });
    EXPECT_NE(m.find("for 1000000 pattern samples"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the samples per stitch or raise the memory budget"), std::string::npos) << m;
    p.samplesPerStitch = 24;
    EXPECT_EQ(knit::generateStockinette(p).points.size(), 24u);
}

// One open curve of 200 points as tubes: 200 rings (+2 caps) of sides + 1 vertices.
struct TubeExport {
    explicit TubeExport(const std::string& path) {
        std::vector<glm::dvec3> points;
        for (int i = 0; i < 200; ++i) points.emplace_back(0.01 * i, 0.0, 0.0);
        curves.addCurve(points.data(), points.size(), false);
        input.curves = &curves;
        input.radius = 0.001;
        options.path = path;
        options.what = knit::ExportWhat::Tubes;
    }
    knit::Polylines curves;
    knit::ExportInput input;
    knit::ExportOptions options;
};

TEST(Budget, tubesOfManySidesAreRefusedBeforeSweepingNamingSides) {
    knit::test::TempDir tmp;
    TubeExport t(tmp.file("t.obj"));
    t.options.sides = 1024;  // 202 x 1025 vertices x 52 B + 2 x 1024 x 200 triangles x 12 B = 15.7 MB
    t.options.budget = MemoryBudget(uint64_t(8) << 20);
    const std::string m = errorOf([&] { knit::exportCurves(t.input, t.options); });
    EXPECT_NE(m.find("2.07e+05 tube vertices per chunk (1024 sides) x 1 chunk in memory at once"), std::string::npos)
        << m;
    EXPECT_NE(m.find("lower the number of tube sides or the vertices per chunk or raise the memory budget"),
              std::string::npos)
        << m;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("t.obj")));
    t.options.sides = 8;
    EXPECT_GT(knit::exportCurves(t.input, t.options).triangles, 0u);
}

TEST(Budget, dracoQuantizationBitsCountInTheTubeExportEstimate) {
    knit::test::TempDir tmp;
    TubeExport t(tmp.file("t.glb"));
    t.options.draco = true;
    t.options.dracoBits = 30;  // Draco's tables: 4 GiB per chunk at 30 bits
    t.options.budget = MemoryBudget(uint64_t(256) << 20);
    const std::string m = errorOf([&] { knit::exportCurves(t.input, t.options); });
    EXPECT_NE(m.find("Draco at 30 bits"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the Draco position bits"), std::string::npos) << m;
    t.options.dracoBits = 16;
    EXPECT_GT(knit::exportCurves(t.input, t.options).triangles, 0u);
}

#ifdef KNIT_HARD_HAVE_RENDER_CHECK
TEST(Budget, renderImageAndTubeGeometryAreRefusedBeforeAllocating) {
    const knit::Scene scene = knit::buildScene(smallPlane());
    knit::RenderOptions o;
    o.spp = 1;
    o.progress = false;
    o.width = o.height = 4096;  // 1.7e7 pixels x 64 B = 1 GiB
    o.budget = MemoryBudget(uint64_t(256) << 20);
    std::string m = errorOf([&] { knit::renderScene(scene, o); });
    EXPECT_NE(m.find("for 1.68e+07 pixels of the image"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the image width or the image height"), std::string::npos) << m;
    o.width = o.height = 16;
    o.mode = knit::GeometryMode::Tubes;
    o.tubeSides = 4096;
    m = errorOf([&] { knit::renderScene(scene, o); });
    EXPECT_NE(m.find("tube triangles"), std::string::npos) << m;
    EXPECT_NE(m.find("lower the traced tube sides"), std::string::npos) << m;
    o.tubeSides = 8;
    EXPECT_EQ(knit::renderScene(scene, o).image.width, 16);
}
#endif

}  // namespace
