// `knit animate` and `knit build --rest` end to end: frame k equals the static reference, bad
// frames and interrupted runs leave no partial cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "animate_sequence.hpp"
#include "common/animated_gltf.hpp"
#include "common/run_knit.hpp"
#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace fs = std::filesystem;

namespace knit::test {
namespace {

class Animate : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_animate_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    // `knit build --rest frame_0001.obj --mesh <frame> -o b.obj`: the static reference of a frame.
    std::vector<glm::dvec3> buildRestReference(const std::string& frame) const {
        const CliRun r = runKnit("build -q --rest frame_0001.obj --mesh " + frame + " --repeats 3 3 -o b.obj", dir);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return objVertices((dir / "b.obj").string());
    }
    fs::path dir;
};

TEST_F(Animate, frameKEqualsBuildRestOnFrameK) {
    writeWaveSequence(dir, 5, 8);
    const CliRun r = runKnit("animate -q --frames frame_%04d.obj --repeats 3 3 -o f_%04d.obj --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<glm::dvec3> a = objVertices((dir / "f_0004.obj").string());
    const std::vector<glm::dvec3> b = buildRestReference("frame_0004.obj");
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 100u);
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "r.json"));
    const double radius = report["yarnRadius"];
    for (size_t i = 0; i < a.size(); ++i) ASSERT_LE(glm::length(a[i] - b[i]), 1e-4 * radius) << "vertex " << i;
    ASSERT_EQ(report["frames"].size(), 5u);
    EXPECT_EQ(report["frames"][0]["maxStretch"], 1.0);
    EXPECT_GT(report["frames"][4]["maxStretch"].get<double>(), 1.0);
    for (const char* key : {"min", "median", "max"}) EXPECT_GT(report["frameSeconds"][key].get<double>(), 0.0);
    EXPECT_GT(report["peakMemoryBytes"].get<double>(), 0.0);
    EXPECT_TRUE(report["frames"][4]["minYarnDistance"].is_number());
    EXPECT_GT(report["stageSeconds"]["stats"].get<double>(), 0.0);
}

// The statistics exist for the report only: --no-stats leaves them out, and a run without a
// report does not compute them (its progress line has no stretch).
TEST_F(Animate, statisticsAreComputedForTheReportOnly) {
    writeWaveSequence(dir, 2, 8);
    CliRun r = runKnit("animate -q --no-stats --frames frame_%04d.obj --repeats 3 3 -o c.pc2 --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "r.json"));
    EXPECT_FALSE(report["frames"][1].contains("minYarnDistance"));
    EXPECT_EQ(report["stageSeconds"]["stats"].get<double>(), 0.0);
    r = runKnit("animate --frames frame_%04d.obj --repeats 3 3 -o d.pc2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frame 2 (2/2)"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("stretch"), std::string::npos) << r.output;
    r = runKnit("animate --frames frame_%04d.obj --repeats 3 3 -o e.pc2 --report s.json", dir);
    EXPECT_NE(r.output.find("min yarn distance"), std::string::npos) << r.output;
}

// -q prints nothing but errors and warnings, on every command that takes it: no progress, and
// no summary line on stdout either (animate printed its "animated ... wrote" line).
TEST_F(Animate, quietPrintsNothingButErrors) {
    writeWaveSequence(dir, 2, 8);
    CliRun r = runKnit("animate --no-stats --frames frame_%04d.obj --repeats 3 3 -o loud.pc2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("animated 2 frames"), std::string::npos) << r.output;
    for (const char* quiet : {"animate -q --no-stats --frames frame_%04d.obj --repeats 3 3 -o q.pc2",
                              "bind -q --mesh frame_0001.obj --repeats 3 3 -o q.knitbind",
                              "build -q --mesh frame_0001.obj --repeats 3 3 --export yarns -o q.obj"}) {
        r = runKnit(quiet, dir);
        EXPECT_EQ(r.exitCode, 0) << quiet;
        EXPECT_EQ(r.output, "") << quiet;
    }
    r = runKnit("animate -q --frames frame_%04d.obj --repeats 3 3 --step 0 -o q.pc2", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--step"), std::string::npos) << r.output;  // errors still say what is wrong
}

TEST_F(Animate, pointCacheHoldsEveryFramesPliesAndTheTopology) {
    writeWaveSequence(dir, 4, 8);
    const CliRun r = runKnit("animate -q --frames . --repeats 3 3 -o c.pc2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<glm::dvec3> ref = buildRestReference("frame_0003.obj");
    const std::vector<glm::dvec3> cached = pc2Frame((dir / "c.pc2").string(), 2);
    ASSERT_EQ(cached.size(), ref.size());
    for (size_t i = 0; i < ref.size(); ++i) ASSERT_LE(glm::length(cached[i] - ref[i]), 1e-6) << "point " << i;
    EXPECT_EQ(objVertices((dir / "c.obj").string()).size(), ref.size());
}

// The library names the frame sequence and its settings in words; the CLI adds its flags.
TEST_F(Animate, frameSequenceErrorsNameTheFlags) {
    writeWaveSequence(dir, 2, 4);
    CliRun r = runKnit("animate -q --frames frames.obj --repeats 3 3 -o c.pc2", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("the frame sequence (--frames): 'frames.obj' is neither a folder nor a file pattern"),
              std::string::npos)
        << r.output;
    r = runKnit("animate -q --frames frame_%04d.obj --step 0 --repeats 3 3 -o c.pc2", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--step"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "c.pc2"));
}

TEST_F(Animate, badFrameFailsNamingItAndLeavesNoPartialCache) {
    writeWaveSequence(dir, 5, 8);
    writeWaveFrame(dir / "frame_0004.obj", 4, 9);  // another resolution: another vertex count
    const std::vector<std::string> before = files();
    const CliRun r = runKnit("animate -q --frames frame_%04d.obj --repeats 3 3 -o c.mdd", dir);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("knit: error: frame 4 ('./frame_0004.obj'): has 100 vertices but the rest mesh 81"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(files(), before);  // no cache, no topology, no temporary file
}

TEST_F(Animate, buildRestRefusesOutputsThatAreTheRestMesh) {
    writeWaveSequence(dir, 2, 8);
    std::ifstream restIn(dir / "frame_0001.obj");
    const std::string rest((std::istreambuf_iterator<char>(restIn)), std::istreambuf_iterator<char>());
    fs::create_directories(dir / "sub");
    // -o through "sub/.." and --report by another spelling: refused by file identity.
    for (const std::string& outputs :
         {std::string("-o sub/../frame_0001.obj"), std::string("-o b.obj --report ./frame_0001.obj")}) {
        const CliRun r = runKnit("build -q --rest frame_0001.obj --mesh frame_0002.obj --repeats 3 3 " + outputs, dir);
        EXPECT_EQ(r.exitCode, 1) << outputs << "\n" << r.output;
        EXPECT_NE(r.output.find("and --rest 'frame_0001.obj' name the same file"), std::string::npos) << r.output;
        std::ifstream after(dir / "frame_0001.obj");
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after)), std::istreambuf_iterator<char>()), rest);
        EXPECT_FALSE(fs::exists(dir / "b.obj"));
    }
}

TEST_F(Animate, sigtermMidRunLeavesNoPartialCacheAndNoTempFile) {
    writeWaveSequence(dir, 400, 16);
    const std::vector<std::string> before = files();
    // Start the run, wait for its temporary cache to appear (in the outputs' staging folder), then send SIGTERM.
    const std::string script =
        "'" + std::string(test::knitCli()) +
        "' animate -q --frames frame_%04d.obj --repeats 6 6 -o c.pc2 > log.txt 2>&1 & "
        "pid=$!; for i in $(seq 1 2000); do ls .knit-staging.*/.c.pc2.*.tmp >/dev/null 2>&1 && break; sleep 0.005; "
        "done; "
        "kill -TERM $pid; wait $pid; echo rc=$?";
    const CliRun r = runShell(script, dir);
    EXPECT_NE(r.output.find("rc=1"), std::string::npos) << r.output;
    std::vector<std::string> after = files();
    after.erase(std::remove(after.begin(), after.end(), "log.txt"), after.end());
    EXPECT_EQ(after, before);
    std::ifstream log(dir / "log.txt");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("interrupted by signal 15"), std::string::npos) << text;
}

// SIGKILL cannot be caught: the killed run leaves its staging folder. The previous cache is
// untouched, and the next run writing into that folder removes the dead run's staging folder.
TEST_F(Animate, sigkillMidCacheKeepsThePreviousCacheAndTheNextRunCleansUp) {
    writeWaveSequence(dir, 400, 16);
    const std::string run =
        "'" + std::string(test::knitCli()) + "' animate -q --no-stats --frames frame_%04d.obj --repeats 6 6 -o c.pc2";
    CliRun r = runShell(run + " --last 3", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string previous = readText((dir / "c.pc2").string());
    ASSERT_GT(previous.size(), 1000u);
    r = runShell(run + " > log.txt 2>&1 & pid=$!; for i in $(seq 1 2000); do "
                       "ls .knit-staging.*/.c.pc2.*.tmp >/dev/null 2>&1 && break; sleep 0.005; done; "
                       "kill -KILL $pid; wait $pid; echo rc=$?",
                 dir);
    EXPECT_NE(r.output.find("rc=137"), std::string::npos) << r.output;  // 128 + SIGKILL
    EXPECT_EQ(readText((dir / "c.pc2").string()), previous);
    const auto staging = [&] {
        std::vector<std::string> left;
        for (const std::string& name : files())
            if (name.rfind(".knit-staging.", 0) == 0 || name.find(".tmp") != std::string::npos) left.push_back(name);
        return left;
    };
    ASSERT_EQ(staging().size(), 1u);  // what the kill left: the staging folder with the partial cache
    r = runShell(run + " --last 3", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(staging(), std::vector<std::string>{});
    EXPECT_EQ(readText((dir / "c.pc2").string()), previous);
}

TEST_F(Animate, animatedGlbMorphTargetKEqualsCacheFrameK) {
    writeWaveSequence(dir, 4, 8);
    CliRun r = runKnit("animate -q --no-stats --frames frame_%04d.obj --repeats 3 3 --fps 10 -o a.glb", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = runKnit("animate -q --no-stats --frames frame_%04d.obj --repeats 3 3 -o c.pc2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectGltfValid((dir / "a.glb").string());
    const gltf::Document d = loadGltf((dir / "a.glb").string());
    const gltf::MeshInstance inst = d.meshInstances().at(0);
    const gltf::Primitive prim = d.primitives(inst.mesh).at(0);
    EXPECT_EQ(prim.mode, 1u);  // LINES
    const std::vector<glm::dvec3> base = worldPositions(d, prim, inst.world);
    ASSERT_EQ((*prim.object)["targets"].size(), 4u);
    for (int k = 0; k < 4; ++k) {
        const std::vector<double> delta =
            readAccessor(d, (*prim.object)["targets"][size_t(k)]["POSITION"].get<size_t>());
        const std::vector<glm::dvec3> cached = pc2Frame((dir / "c.pc2").string(), k);
        ASSERT_EQ(cached.size(), base.size());
        for (size_t i = 0; i < base.size(); ++i) {
            const glm::dvec3 p = base[i] + glm::dvec3(delta[3 * i], delta[3 * i + 1], delta[3 * i + 2]);
            ASSERT_LE(glm::length(p - cached[i]), 1e-6) << "frame " << k << " point " << i;
        }
    }
    const std::vector<double> times = readAccessor(d, d.root()["animations"][0]["samplers"][0]["input"].get<size_t>());
    ASSERT_EQ(times.size(), 4u);
    EXPECT_FLOAT_EQ(times[3], 0.3f);
}

TEST_F(Animate, animatedGlbOfTubesHasTrianglesWithNormalTargetsAndIsValid) {
    writeWaveSequence(dir, 3, 8);
    const CliRun r =
        runKnit("animate -q --no-stats --frames frame_%04d.obj --repeats 3 3 --export tubes --linear -o t.glb", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectGltfValid((dir / "t.glb").string());
    const gltf::Document d = loadGltf((dir / "t.glb").string());
    const gltf::Primitive prim = d.primitives(0).at(0);
    EXPECT_EQ(prim.mode, 4u);  // TRIANGLES
    ASSERT_EQ((*prim.object)["targets"].size(), 3u);
    EXPECT_TRUE((*prim.object)["targets"][2].contains("NORMAL"));
    // The last frame's tubes moved: the wave lifts them, so its POSITION deltas are not zero.
    const std::vector<double> delta = readAccessor(d, (*prim.object)["targets"][2]["POSITION"].get<size_t>());
    double largest = 0;
    for (double v : delta) largest = std::max(largest, std::abs(v));
    EXPECT_GT(largest, 1e-3);
    EXPECT_FALSE(d.attribute(prim, "COLOR_0").has_value());  // the built-in stockinette has no colours
    EXPECT_EQ(d.root()["animations"][0]["samplers"][0]["interpolation"], "LINEAR");
}

// A chart with a colour layer: the animated GLB (ply lines and yarn tubes) carries the chart's
// colours as COLOR_0, one per vertex, both stripes present (red #d62828, blue #1d3557).
TEST_F(Animate, animatedGlbCarriesTheChartsColoursAsColor0) {
    writeWaveSequence(dir, 2, 8);
    std::ofstream(dir / "stripes.chart") << "k k\nk k\n\nB B\nA A\nA=#d62828 B=#1d3557\n";
    for (const std::string args : {"-o lines.glb", "--export tubes --tubes-of yarns -o tubes.glb"}) {
        const std::string out = args.substr(args.rfind(' ') + 1);
        const CliRun r =
            runKnit("animate -q --no-stats --pattern stripes.chart --frames frame_%04d.obj --repeats 3 3 " + args, dir);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        expectGltfValid((dir / out).string());
        const gltf::Document d = loadGltf((dir / out).string());
        const gltf::Primitive prim = d.primitives(0).at(0);
        const std::vector<double> rgba = readAttribute(d, prim, "COLOR_0");
        const std::vector<double> xyz = readAttribute(d, prim, "POSITION");
        ASSERT_EQ(rgba.size() / 4, xyz.size() / 3) << out;
        size_t red = 0, blue = 0;
        for (size_t i = 0; i < rgba.size(); i += 4) {
            red += rgba[i] > 0.5 && rgba[i + 2] < 0.1;
            blue += rgba[i + 2] > rgba[i] && rgba[i] < 0.05;
        }
        EXPECT_GT(red, 0u) << out;
        EXPECT_GT(blue, 0u) << out;
        EXPECT_EQ(red + blue, rgba.size() / 4) << out;  // every vertex has one of the two
    }
}

TEST_F(Animate, animatedGlbOverTheMemoryBudgetIsRefusedWithItsEstimate) {
    writeWaveSequence(dir, 3, 8);
    const CliRun r =
        runKnit("animate -q --frames frame_%04d.obj --repeats 3 3 --max-memory 300K --export tubes -o a.glb", dir);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("(estimate) for an animated .glb of 3 frames x"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--step"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "a.glb"));
}

TEST_F(Animate, morphAnimatedGltfIsSampledAtFpsAndItsLastFrameIsTheFullTarget) {
    const std::string gltf = writeMorphQuad(dir.string());
    const CliRun r = runKnit("animate -q --no-stats --frames morph.gltf --fps 4 --repeats 2 2 -o c.pc2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // 5 samples (0 .. 1 s at 4 fps); the quad lifts vertex i by (i + 1) x weight, so the yarns
    // rise: frame 5 (weight 1) spans at least 2 m more in z than frame 1, frame 3 about half that.
    auto zSpan = [&](int k) {
        double lo = 1e9, hi = -1e9;
        for (const glm::dvec3& p : pc2Frame((dir / "c.pc2").string(), k))
            lo = std::min(lo, p.z), hi = std::max(hi, p.z);
        return hi - lo;
    };
    const double rise = zSpan(4) - zSpan(0);
    EXPECT_GT(rise, 2.0);
    EXPECT_NEAR(zSpan(2) - zSpan(0), 0.5 * rise, 0.15 * rise);  // weight 0.5 at t = 0.5 s
    const CliRun bad = runKnit("animate -q --frames morph.gltf --last 9 -o c.pc2", dir);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.output.find("frame 3 is missing: 'morph.gltf' has 2 samples"), std::string::npos) << bad.output;
}

TEST_F(Animate, unsupportedOutputsAreRefusedBeforeAnyWork) {
    writeWaveSequence(dir, 2, 4);
    CliRun r = runKnit("animate -q --frames frame_%04d.obj --export tubes --draco -o out.glb", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("an animated .glb holds plain float morph targets"), std::string::npos) << r.output;
    r = runKnit("animate -q --frames frame_%04d.obj -o out.gltf", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("one animated out.glb"), std::string::npos) << r.output;
    r = runKnit("animate -q --frames frame_%04d.obj --export tubes -o out.pc2", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("point caches hold curve points"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace knit::test
