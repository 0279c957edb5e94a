// `knit render` bad input end to end: exit code 1 (a knit::Error, not an internal error), a
// message naming the problem, and no image (partial or not) left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

#include "common/run_knit.hpp"

namespace fs = std::filesystem;

namespace {

using RenderRun = knit::test::CliRun;
RenderRun knitIn(const fs::path& cwd, const std::string& args) { return knit::test::runKnit(args, cwd); }

// A scene that builds and renders in a fraction of a second.
const std::string kSmall = "render -q --mesh plane --repeats 2 2 --mesh-res 4 --width 16 --height 12 ";

class RenderCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_render_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        if (knitIn(dir, "render --help").exitCode != 0) GTEST_SKIP() << "knit was built without render_check";
    }
    void TearDown() override { fs::remove_all(dir); }
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto& e : fs::recursive_directory_iterator(dir))
            if (e.is_regular_file()) names.push_back(e.path().lexically_relative(dir).string());
        return names;
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
    // Runs a render expected to fail: exit 1, message with every fragment, no file but `keep`.
    void expectCleanError(const std::string& args, const std::vector<std::string>& fragments,
                          const std::vector<std::string>& keep = {}) {
        const RenderRun r = knitIn(dir, kSmall + args);
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
        for (const std::string& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos) << "'" << f << "' in: " << r.output;
        std::vector<std::string> left = files();
        std::sort(left.begin(), left.end());
        std::vector<std::string> expected = keep;
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(left, expected) << args;
    }
    fs::path dir;
};

TEST_F(RenderCli, smallRenderWritesPngExrAndReport) {
    // The baseline the error cases differ from by one flag.
    const RenderRun r = knitIn(dir, kSmall + "--spp 2 --output o.png --exr o.exr --report r.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::vector<std::string> left = files();
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"o.exr", "o.png", "r.json"}));
    EXPECT_GT(fs::file_size(dir / "o.png"), 0u);
}

TEST_F(RenderCli, zeroSamplesPerPixelIsAnErrorWithNoImage) {
    expectCleanError("--spp 0 --output o.png --exr o.exr", {"samples per pixel", "got 0"});
    expectCleanError("--spp -2 --output o.png", {"samples per pixel", "got -2"});
}

TEST_F(RenderCli, outputInMissingFolderNamesThePath) {
    expectCleanError("--spp 1 --output missing/o.png", {"missing/o.png", "does not exist"});
}

TEST_F(RenderCli, outputThatIsAFolderNamesThePath) {
    fs::create_directories(dir / "taken.png");
    const RenderRun r = knitIn(dir, kSmall + "--spp 1 --output taken.png");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("taken.png"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("a folder with that name exists"), std::string::npos) << r.output;  // as `build` says
    EXPECT_TRUE(fs::is_directory(dir / "taken.png"));
    EXPECT_TRUE(files().empty());
}

TEST_F(RenderCli, unwritableExrPathLeavesNoPngEither) {
    // Both paths are checked before rendering, so the PNG is not written when the EXR cannot be.
    expectCleanError("--spp 1 --output o.png --exr missing/o.exr", {"missing/o.exr"});
}

TEST_F(RenderCli, missingMaterialFileIsNamed) {
    expectCleanError("--spp 1 --output o.png --material nothere.json", {"nothere.json", "cannot be opened"});
}

TEST_F(RenderCli, materialFileThatIsAFolderIsNamed) {
    fs::create_directories(dir / "mat.json");
    const RenderRun r = knitIn(dir, kSmall + "--spp 1 --output o.png --material mat.json");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("mat.json"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("directory"), std::string::npos) << r.output;
    EXPECT_TRUE(files().empty());
}

TEST_F(RenderCli, malformedMaterialJsonIsNamed) {
    write("mat.json", "{\"kR\": 0.3,\n");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"mat.json", "invalid JSON", "line 2"},
                     {"mat.json"});
    write("mat.json", "[0.3, 0.4]");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"mat.json", "JSON object"}, {"mat.json"});
    write("mat.json", "{\"kR\": \"shiny\"}");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"mat.json", "'kR'"}, {"mat.json"});
}

TEST_F(RenderCli, outOfRangeMaterialValuesAreNamed) {
    write("mat.json", "{\"alphaAlong\": 3}");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"mat.json", "'alphaAlong'", "out of range"},
                     {"mat.json"});
    write("mat.json", "{\"bodyAlbedo\": [0.5, -0.1, 0.5]}");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"'bodyAlbedo'", "channel g"}, {"mat.json"});
    write("mat.json", "{\"kR\": 0.8, \"bodyAlbedo\": 0.5}");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"mat.json", "energy bound"}, {"mat.json"});
    write("mat.json", "{\"glossiness\": 1}");
    expectCleanError("--spp 1 --output o.png --material mat.json", {"unknown field 'glossiness'"}, {"mat.json"});
    // Flags are validated the same way.
    expectCleanError("--spp 1 --output o.png --kTT 0.9 --body-albedo 0.3", {"energy bound"}, {"mat.json"});
}

}  // namespace
