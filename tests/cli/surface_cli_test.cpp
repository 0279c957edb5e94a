// `knit build --surface-only --bake-size N`: the base mesh with the baked knit material.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "common/run_knit.hpp"
#include "export/gltf_validator.hpp"

namespace fs = std::filesystem;

namespace {

class SurfaceCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_surface_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

TEST_F(SurfaceCli, surfaceOnlyWritesTheBaseMeshWithTheBakedMaterial) {
    const auto r = knit::test::runKnit(
        "build -q --surface-only --bake-size 16 --mesh-res 4 --repeats 3 3 -o s.glb --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "r.json"));
    EXPECT_EQ(report["surface"]["bakeWidth"], 16);
    EXPECT_EQ(report["export"]["bytes"].get<size_t>(), fs::file_size(dir / "s.glb"));
    const double coverage = report["surface"]["meanCoverage"];
    EXPECT_GT(coverage, 0.0);
    EXPECT_LT(coverage, 1.0);
    EXPECT_EQ(report["surface"]["repeats"], nlohmann::json::array({3.0, 3.0}));
    knit::test::expectGltfValid((dir / "s.glb").string());
}

TEST_F(SurfaceCli, badBakeSizeNamesTheOptionAndLeavesNoFile) {
    const auto r = knit::test::runKnit("build -q --surface-only --bake-size 0 -o s.glb", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("--bake-size"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST_F(SurfaceCli, surfaceOnlyRefusesAnOutputThatIsNotGlb) {
    const auto r = knit::test::runKnit("build -q --surface-only --bake-size 8 --mesh-res 4 -o s.obj", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("s.obj"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
