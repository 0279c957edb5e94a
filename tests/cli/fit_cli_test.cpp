// `knit fit` end to end on a tiny scene: a fit writes a material `knit render --material` reads and
// a report with its images; bad photographs, masks and bounds exit 1 naming the file or option
// and leave no material behind; a uniform target ends with a warning and the best fit (exit 0).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include "common/run_knit.hpp"

namespace fs = std::filesystem;

namespace {

using knit::test::CliRun;

// A scene that builds in a fraction of a second; cheap fiber tables keep each render short.
const std::string kPlane = "--mesh plane --repeats 2 2 --mesh-res 4 ";
const std::string kScene = kPlane + "--material cheap.json ";
const std::string kFit = "fit -q " + kScene + "--spp 2 --max-evaluations 4 ";

class FitCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_fit_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        if (run("fit --help").exitCode != 0) GTEST_SKIP() << "knit was built without the fit";
        std::ofstream(dir / "cheap.json") << R"({"tableSize": 64, "aoRays": 64})";
        // The targets: the default material rendered front- and back-lit at 32 x 24.
        for (const char* light : {"front", "back"}) {
            const CliRun r = run("render -q " + kScene + "--width 32 --height 24 --spp 4 --seed 9 --light " + light +
                                 " --output " + light + ".png");
            ASSERT_EQ(r.exitCode, 0) << r.output;
        }
    }
    void TearDown() override { fs::remove_all(dir); }
    CliRun run(const std::string& args) const { return knit::test::runKnit(args, dir); }
    void writePng(const std::string& name, int w, int h, unsigned char value) const {
        const std::vector<unsigned char> px(size_t(3) * w * h, value);
        ASSERT_TRUE(stbi_write_png((dir / name).c_str(), w, h, 3, px.data(), 3 * w));
    }
    // A fit expected to fail: exit 1, every fragment in the message, no material written.
    void expectCleanError(const std::string& args, const std::vector<std::string>& fragments) const {
        const CliRun r = run(kFit + args + " -o m.json");
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
        for (const std::string& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos) << "'" << f << "' in: " << r.output;
        EXPECT_FALSE(fs::exists(dir / "m.json")) << args;
    }
    fs::path dir;
};

TEST_F(FitCli, fitWritesMaterialThatRenderReadsAndReportWithImages) {
    const CliRun r = run("fit " + kScene +
                         "--spp 2 --max-evaluations 4 --front front.png --back back.png -o m.json "
                         "--report r.json");  // not quiet: progress on stderr
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("evaluation 1"), std::string::npos) << r.output;  // progress on stderr
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "r.json"));
    EXPECT_EQ(report["history"].size(), 4u);
    EXPECT_EQ(report["renders"], 8);
    EXPECT_TRUE(report["parameters"].contains("kR"));
    EXPECT_TRUE(report["parameters"].contains("body-albedo.g"));
    EXPECT_GT(report["front"]["ssim"].get<double>(), 0.0);
    for (const char* png : {"r_front.png", "r_back.png", "r_side_by_side.png"}) EXPECT_TRUE(fs::exists(dir / png));
    const CliRun render =
        run("render -q " + kPlane + "--width 16 --height 12 --spp 1 --material m.json --output o.png");
    EXPECT_EQ(render.exitCode, 0) << render.output;
}

// EXR photographs are linear radiance, compared unclipped: targets rendered to EXR fit as well as
// the PNG ones (the same renders), and the report's loss is finite.
TEST_F(FitCli, exrPhotographsAreReadAsLinearRadiance) {
    for (const char* light : {"front", "back"}) {
        const CliRun r = run("render -q " + kScene + "--width 32 --height 24 --spp 4 --seed 9 --light " + light +
                             " --output " + light + "2.png --exr " + light + ".exr");
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    const CliRun r = run(kFit + "--front front.exr --back back.exr -o m.json --report exr.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "exr.json"));
    EXPECT_GT(report["front"]["ssim"].get<double>(), 0.5);
    EXPECT_TRUE(std::isfinite(report["loss"].get<double>()));
    std::ofstream(dir / "junk.exr") << "not an exr";
    fs::remove(dir / "m.json");
    expectCleanError("--front junk.exr --back back.exr", {"--front 'junk.exr'"});
}

TEST_F(FitCli, mismatchedImageSizesNameBothPhotographs) {
    writePng("small.png", 16, 12, 100);
    expectCleanError("--front front.png --back small.png", {"--back 'small.png' is 16 x 12", "front.png", "same size"});
}

TEST_F(FitCli, unreadableImageNamesTheFile) {
    std::ofstream(dir / "junk.png") << "not a png";
    expectCleanError("--front junk.png --back back.png", {"--front 'junk.png'", "cannot read"});
    expectCleanError("--front front.png --back missing.png", {"--back 'missing.png'", "does not exist"});
}

TEST_F(FitCli, maskOfTheWrongSizeNamesTheMask) {
    writePng("mask.png", 16, 12, 255);
    expectCleanError("--front front.png --back back.png --mask mask.png", {"--mask 'mask.png'", "16 x 12", "32 x 24"});
}

TEST_F(FitCli, boundsThatBreakEnergyConservationNameTheOption) {
    expectCleanError(
        "--front front.png --back back.png --fit kR,body-albedo --bound kR=0:0.9 --bound body-albedo=0.3:1",
        {"--bound", "energy bound"});
    expectCleanError("--front front.png --back back.png --bound kR=0:1.5", {"--bound 'kR=0:1.5'", "[0, 1]"});
    expectCleanError("--front front.png --back back.png --fit kR,shininess", {"--fit", "'shininess'"});
}

TEST_F(FitCli, solidColourTargetEndsWithWarningAndBestFit) {
    writePng("grey_f.png", 32, 24, 128);
    writePng("grey_b.png", 32, 24, 128);
    const CliRun r = run(kFit + "--front grey_f.png --back grey_b.png -o m.json");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warning: --front 'grey_f.png' is uniform"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "m.json"));
}

}  // namespace

// The camera flags reach the fit's renders: targets rendered from a closer, oblique camera are
// matched far better with that camera than with the default framing; a bad camera is named.
TEST_F(FitCli, fitRendersFromTheCameraOfThePhotographs) {
    ASSERT_EQ(run("render -q " + kScene + "--width 8 --height 6 --spp 1 --output d.png --report d.json").exitCode, 0);
    const nlohmann::json framing = nlohmann::json::parse(std::ifstream(dir / "d.json"))["camera"];
    std::string eye, target, up;
    for (int k = 0; k < 3; ++k) {
        up += std::to_string(framing["up"][k].get<double>()) + " ";
        const double t = framing["target"][k].get<double>(), e = framing["eye"][k].get<double>();
        const double offset = (k == 0 ? 0.3 : 0.0) * std::abs(e - t);  // halfway in, turned sideways
        target += std::to_string(t) + " ";
        eye += std::to_string(t + 0.5 * (e - t) + offset) + " ";
    }
    const std::string camera = "--eye " + eye + "--target " + target + "--up " + up;
    for (const char* light : {"front", "back"}) {
        const CliRun r = run("render -q " + kScene + camera + "--width 32 --height 24 --spp 4 --seed 9 --light " +
                             light + " --output cam_" + light + ".png");
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    auto fitLoss = [&](const std::string& flags, const std::string& report) {
        const CliRun r = run(kFit + flags + "--front cam_front.png --back cam_back.png -o m.json --report " + report);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return nlohmann::json::parse(std::ifstream(dir / report))["loss"].get<double>();
    };
    const double withCamera = fitLoss(camera, "with.json"), framed = fitLoss("", "framed.json");
    EXPECT_LT(withCamera, 0.5 * framed) << "the fit did not render from --eye/--target";
    // --detail view (the default) builds only the cells the camera sees (here all four: culling
    // itself is tested in tests/lod/detail_test.cpp), all at the ply level; --detail full fits
    // as well.
    const nlohmann::json with = nlohmann::json::parse(std::ifstream(dir / "with.json"));
    EXPECT_EQ(with["detail"], "view");
    EXPECT_GT(with["levels"]["plies"]["cells"].get<int>(), 0);
    EXPECT_EQ(with["levels"]["yarns"]["cells"].get<int>(), 0);
    EXPECT_EQ(with["levels"]["surface"]["cells"].get<int>(), 0);
    const double full = fitLoss(camera + "--detail full ", "full.json");
    EXPECT_NEAR(full, withCamera, 0.1 * withCamera);
    std::printf("fit loss with the photographs' camera %.4g, with the default framing %.4g\n", withCamera, framed);
    fs::remove(dir / "m.json");
    expectCleanError("--front cam_front.png --back cam_back.png --eye 0 0 0 --target 0 0 0",
                     {"the eye position (--eye) and the target position (--target) must differ"});
    const CliRun sized = run(kFit + "--front cam_front.png --back cam_back.png --width 16 -o m.json");
    EXPECT_NE(sized.exitCode, 0) << "the photographs fix the image size";
    EXPECT_NE(sized.output.find("--width"), std::string::npos) << sized.output;
}
