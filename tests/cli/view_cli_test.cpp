// The view flags of `knit build` and `knit render` end to end: bad views are refused naming the
// option (exit 1, no output file), the camera and the levels are in both reports, and
// `--detail view` keeps fewer ply vertices than `--detail full` for a close view.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "common/run_knit.hpp"
#include "export/gltf_validator.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kScene = " -q --mesh plane --repeats 4 4 --mesh-res 4 ";

class ViewCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_view_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    knit::test::CliRun run(const std::string& args) const { return knit::test::runKnit(args, dir); }
    nlohmann::json report(const std::string& name) const { return nlohmann::json::parse(std::ifstream(dir / name)); }
    bool hasRender() const { return run("render --help").exitCode == 0; }
    fs::path dir;
};

TEST_F(ViewCli, badViewsNameTheOptionAndWriteNothing) {
    const std::pair<const char*, const char*> cases[] = {
        {"--eye 0 1 0 --target 0 1 0", "the eye position (--eye) and the target position (--target) must differ"},
        {"--eye 0 1 0 --target 0 0 0 --up 0 -3 0", "--up"},
        {"--eye 0 1 0.2 --target 0 0 0 --fov 0", "--fov"},
        {"--eye 0 1 0.2 --target 0 0 0 --fov 180", "--fov"},
        {"--eye nan 1 0 --target 0 0 0", "--eye"},
        {"--eye 0 1 0.2 --target 0 inf 0", "--target"},
        {"--eye 0 1 0.2 --target 0 0 0 --width 0", "--width"},
    };
    for (const auto& [flags, message] : cases) {
        const knit::test::CliRun b = run("build" + kScene + "-o out.obj " + flags);
        EXPECT_EQ(b.exitCode, 1) << flags << "\n" << b.output;
        EXPECT_NE(b.output.find(message), std::string::npos) << flags << "\n" << b.output;
        EXPECT_FALSE(fs::exists(dir / "out.obj")) << flags;
        if (!hasRender()) continue;
        const knit::test::CliRun r = run("render" + kScene + "--spp 1 --output out.png " + std::string(flags));
        EXPECT_EQ(r.exitCode, 1) << flags << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << flags << "\n" << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << flags;
    }
}

TEST_F(ViewCli, detailViewIsRefusedForARestPoseFrame) {
    const knit::test::CliRun b = run("build" + kScene + "--rest plane -o out.obj --detail view");
    EXPECT_EQ(b.exitCode, 1) << b.output;
    EXPECT_NE(b.output.find("--detail view does not apply to --rest"), std::string::npos) << b.output;
    EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST_F(ViewCli, buildReportsCameraAndLevelsAndViewKeepsLessThanFull) {
    ASSERT_EQ(run("build" + kScene + "-o full.obj --report full.json").exitCode, 0);
    const std::string close = "--detail view --eye 0.1 0.15 0.1 --target 0.1 0 0.1 --up 0 0 -1 --width 64 --height 48";
    ASSERT_EQ(run("build" + kScene + "-o view.obj --report view.json " + close).exitCode, 0);
    const nlohmann::json full = report("full.json"), view = report("view.json");
    EXPECT_EQ(view["camera"]["eye"], nlohmann::json({0.1, 0.15, 0.1}));
    EXPECT_EQ(view["camera"]["fovDegrees"], 30.0);
    EXPECT_EQ(full["levels"]["plies"]["cells"], full["counts"]["cells"]);
    EXPECT_EQ(full["levels"]["plies"]["plyVertices"], full["vertices"]["ply"]);
    EXPECT_GT(view["levels"]["culledCells"].get<int>(), 0);
    EXPECT_LT(view["levels"]["plies"]["plyVertices"].get<size_t>(),
              full["levels"]["plies"]["plyVertices"].get<size_t>());
    EXPECT_LT(fs::file_size(dir / "view.obj"), fs::file_size(dir / "full.obj"));
    EXPECT_EQ(view["levels"]["surface"]["textured"], false);
}

// A far view (8 x 6 pixels: every cell below a pixel) writes the base mesh with the baked material
// and no curves: a fraction of the full file, valid for the Khronos validator.
TEST_F(ViewCli, buildFarViewWritesTheTexturedSurfaceLevel) {
    if (!hasRender()) GTEST_SKIP() << "knit was built without render_check (it bakes the surface level)";
    const std::string scene = " -q --mesh drape --repeats 4 4 --mesh-res 8 --bake-size 16 ";
    ASSERT_EQ(run("build" + scene + "-o full.glb").exitCode, 0);
    const knit::test::CliRun r = run("build" + scene + "--detail view --width 8 --height 6 -o far.glb --report r.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = report("r.json");
    EXPECT_EQ(j["levels"]["surface"]["cells"], j["counts"]["cells"]);
    EXPECT_EQ(j["levels"]["surface"]["textured"], true);
    EXPECT_EQ(j["export"]["curves"], 0);
    EXPECT_EQ(j["export"]["surface"]["triangles"], 128);  // every triangle of the 8 x 8 drape
    EXPECT_GT(j["export"]["surface"]["imageBytes"].get<size_t>(), 0u);
    EXPECT_EQ(j["export"]["bytes"].get<size_t>(), fs::file_size(dir / "far.glb"));
    EXPECT_LT(2 * fs::file_size(dir / "far.glb"), fs::file_size(dir / "full.glb"));
    knit::test::expectGltfValid((dir / "far.glb").string());
}

// A grazing view of a plane has all three levels (with plies from 1 pixel: the default 0.5 leaves
// two-ply yarns no yarn level): ply- and yarn-level cells are written as plies, the surface-level
// triangles with the baked material, all in one valid file.
TEST_F(ViewCli, buildMixedViewWritesEveryLevelInOneGltf) {
    if (!hasRender()) GTEST_SKIP() << "knit was built without render_check (it bakes the surface level)";
    const std::string view = " -q --mesh plane --mesh-res 8 --repeats 20 20 --bake-size 16 --detail view "
                             "--eye 0.24 0.03 0.24 --target -0.2 0 -0.2 --width 40 --height 40 --ply-pixels 1 ";
    for (const char* out : {"mixed.glb", "mixed.gltf"}) {
        const knit::test::CliRun r = run("build" + view + "-o " + out + " --report r.json");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const nlohmann::json j = report("r.json");
        for (const char* level : {"plies", "yarns", "surface"}) EXPECT_GT(j["levels"][level]["cells"], 0) << level;
        EXPECT_GT(j["levels"]["culledCells"], 0);
        EXPECT_GT(j["export"]["curves"], 0);
        EXPECT_GT(j["export"]["surface"]["triangles"], 0);
        EXPECT_LT(j["export"]["surface"]["triangles"], 128);
        EXPECT_EQ(j["levels"]["plies"]["plyVertices"], j["export"]["vertices"]);
        knit::test::expectGltfValid((dir / out).string());
    }
    // The same view into a curve format: the surface level cannot go there.
    const knit::test::CliRun obj = run("build" + view + "-o mixed.obj");
    EXPECT_EQ(obj.exitCode, 1);
    EXPECT_NE(obj.output.find("-o 'mixed.obj'"), std::string::npos) << obj.output;
    EXPECT_NE(obj.output.find(".glb or .gltf"), std::string::npos) << obj.output;
    EXPECT_FALSE(fs::exists(dir / "mixed.obj"));
}

// --ply-pixels and --yarn-pixels move the levels' thresholds: finer thresholds keep more cells at
// finer levels; a threshold that is not a positive number is refused, naming the option, before
// anything is built or written.
TEST_F(ViewCli, levelThresholdsMoveTheLevelsAndBadOnesNameTheOption) {
    const std::string view = " -q --mesh plane --mesh-res 8 --repeats 20 20 --detail view --eye 0.24 0.03 0.24 "
                             "--target -0.2 0 -0.2 --width 40 --height 40 -o v.obj --report r.json ";
    ASSERT_EQ(run("build" + view + "--ply-pixels 0.05 --yarn-pixels 0.05").exitCode, 0);
    const nlohmann::json fine = report("r.json");
    ASSERT_EQ(run("build" + view + "--ply-pixels 0.5 --yarn-pixels 0.1").exitCode, 0);
    const nlohmann::json coarse = report("r.json");
    EXPECT_GT(fine["levels"]["plies"]["cells"].get<int>(), coarse["levels"]["plies"]["cells"].get<int>());
    EXPECT_GT(coarse["levels"]["yarns"]["cells"].get<int>(), 0);
    for (const char* bad : {"--ply-pixels 0", "--ply-pixels -1", "--yarn-pixels nan", "--yarn-pixels inf"}) {
        fs::remove(dir / "bad.glb");
        const knit::test::CliRun r = run("build -q --detail view " + std::string(bad) + " -o bad.glb");
        EXPECT_EQ(r.exitCode, 1) << bad;
        const std::string option = std::string(bad).substr(0, std::string(bad).find(' '));
        EXPECT_NE(r.output.find(option), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "bad.glb")) << bad;
    }
}

TEST_F(ViewCli, buildViewThatSeesNoClothSaysSo) {
    const knit::test::CliRun r =
        run("build" + kScene + "--detail view --eye 0 -1 0 --target 0 -2 0 --up 0 0 -1 -o none.glb");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("the view sees none of the cloth"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "none.glb"));
}

TEST_F(ViewCli, renderReportsTheDefaultCameraAndItsLevels) {
    if (!hasRender()) GTEST_SKIP() << "knit was built without render_check";
    ASSERT_EQ(run("render" + kScene + "--spp 1 --width 16 --height 12 --report r.json").exitCode, 0);
    const nlohmann::json r = report("r.json");
    ASSERT_TRUE(r.contains("camera"));
    EXPECT_EQ(r["camera"]["target"], nlohmann::json({0.0, 0.0, 0.0}));  // the plane is centred
    EXPECT_GT(r["camera"]["eye"][1].get<double>(), 0.0);                // in front (+y) of it
    const size_t cells = r["levels"]["plies"]["cells"].get<size_t>() + r["levels"]["yarns"]["cells"].get<size_t>() +
                         r["levels"]["surface"]["cells"].get<size_t>() + r["levels"]["culledCells"].get<size_t>();
    EXPECT_GT(cells, 0u);
    EXPECT_TRUE(r.contains("seconds"));
    EXPECT_TRUE(r.contains("peakMemoryBytes"));
}

// A far view draws the cloth as its surface level: the base mesh with the pattern baked with
// the render's material (textured, the bake timed in the report), not the plain body colour; its
// mean radiance stays near the full-detail render's (the plain surface was 65% brighter on the
// garment, docs/views.md).
TEST_F(ViewCli, farViewRendersTheBakedSurfaceNearTheFullImage) {
    if (!hasRender()) GTEST_SKIP() << "knit was built without render_check";
    const std::string scene = " -q --mesh plane --repeats 40 40 --mesh-res 8 --spp 16 --width 48 --height 36 ";
    ASSERT_EQ(run("render" + scene + "--report view.json").exitCode, 0);
    ASSERT_EQ(run("render" + scene + "--detail full --report full.json").exitCode, 0);
    const nlohmann::json view = report("view.json"), full = report("full.json");
    ASSERT_GT(view["levels"]["surface"]["cells"].get<size_t>(), 0u);
    EXPECT_EQ(view["levels"]["surface"]["textured"], true);
    EXPECT_GT(view["bakeSeconds"].get<double>(), 0.0);
    EXPECT_EQ(full["bakeSeconds"], 0.0);
    for (int c = 0; c < 3; ++c) {
        const double v = view["meanRadiance"][c].get<double>(), f = full["meanRadiance"][c].get<double>();
        EXPECT_NEAR(v / f, 1.0, 0.15) << "channel " << c << ": view " << v << ", full " << f;
    }
}

}  // namespace
