// End-to-end tests of the `knit` command line: exit codes, messages, files left behind.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <sys/wait.h>
#include <vector>

#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include "common/run_knit.hpp"
#include "knit/pattern.hpp"
#include "common/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

using knit::test::CliRun;
CliRun knit(const std::string& args, const fs::path& cwd) { return knit::test::runKnit(args, cwd); }

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    size_t fileCount() const { return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator())); }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
    fs::path dir;
};

std::string shared(const std::string& f) { return std::string(knit::test::sharedDir()) + "/patterns/hylc/" + f; }

TEST_F(Cli, buildWithNoArgumentsWritesDefaultPlies) {
    const CliRun r = knit("build", dir);  // with -q it would print nothing
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(dir / "knit-plies.obj"));
    std::ifstream in(dir / "knit-plies.obj");
    size_t v = 0, l = 0;
    for (std::string line; std::getline(in, line);) {
        v += line.rfind("v ", 0) == 0;
        l += line.rfind("l ", 0) == 0;
    }
    EXPECT_GT(v, 100000u);
    EXPECT_GT(l, 100u);
    EXPECT_NE(r.output.find("yarns"), std::string::npos);
}

TEST_F(Cli, reportHasCountsTimesAndSegmentLengths) {
    const CliRun r = knit("build -q --mesh plane --repeats 10 10 --export yarns -o y.obj --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(dir / "r.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const char* k : {"cells", "yarns", "closed_loops", "open_ends", "cut_vertices", "welded_ends"})
        EXPECT_TRUE(j["counts"].contains(k)) << k;
    // 10 x 10 cells plus the row and column touched by the square's far edges (u = 1, v = 1).
    EXPECT_EQ(j["counts"]["cells"].get<int>(), 121);
    EXPECT_GT(j["yarn_segments"]["longest_segment_length"].get<double>(), 0);
    EXPECT_GT(j["yarn_segments"]["median_segment_length"].get<double>(), 0);
    for (const char* k : {"uv_grid", "tiling", "stitch", "binding", "evaluate", "total"})
        EXPECT_TRUE(j["seconds"].contains(k)) << k;
}

TEST_F(Cli, cylinderWithIntegralRepeatsGivesClosedCourses) {
    const CliRun r = knit("build -q --mesh cylinder --repeats 24 10 --export yarns -o y.obj --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(dir / "r.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_GE(j["counts"]["closed_loops"].get<int>(), 8);
    // Curves are 2-index `l i j` segments; a closed curve ends with the segment back to its
    // first vertex (the only segments whose second index is lower).
    std::ifstream obj(dir / "y.obj");
    bool sawClosed = false;
    for (std::string line; std::getline(obj, line);) {
        if (line.rfind("l ", 0) != 0) continue;
        std::istringstream ss(line.substr(2));
        std::vector<long> idx;
        for (long x; ss >> x;) idx.push_back(x);
        ASSERT_EQ(idx.size(), 2u) << line;
        sawClosed = sawClosed || idx[1] < idx[0];
    }
    EXPECT_TRUE(sawClosed);
}

// The same asset as OBJ and as glTF (v flipped, as glTF stores it) gives the same knit, byte for
// byte: the glTF reader is used by the CLI, which also loads Draco (whose library carries its
// own copy of tinygltf's symbols).
TEST_F(Cli, gltfBaseMeshGivesTheSameKnitAsItsObj) {
    const int n = 8;  // an n x n grid of quads, 0.5 m, gently curved; coordinates exact in float
    std::ostringstream obj;
    std::vector<float> pos, uv;
    std::vector<uint32_t> idx;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = 0.0625f * float(i), y = 0.0625f * float(j), z = 0.015625f * float((i * j) % 3);
            obj << "v " << x << ' ' << y << ' ' << z << "\nvt " << float(i) / n << ' ' << float(j) / n << '\n';
            pos.insert(pos.end(), {x, y, z});
            uv.insert(uv.end(), {float(i) / n, 1.0f - float(j) / n});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n) + 2, d = a + uint32_t(n) + 1;
            obj << "f " << a + 1 << '/' << a + 1 << ' ' << b + 1 << '/' << b + 1 << ' ' << c + 1 << '/' << c + 1
                << "\n";
            obj << "f " << a + 1 << '/' << a + 1 << ' ' << c + 1 << '/' << c + 1 << ' ' << d + 1 << '/' << d + 1
                << "\n";
            idx.insert(idx.end(), {a, b, c, a, c, d});
        }
    write("grid.obj", obj.str());
    // glTF: positions, texcoords and indices in one external buffer.
    std::string bin(reinterpret_cast<const char*>(pos.data()), pos.size() * 4);
    const size_t uvAt = bin.size();
    bin.append(reinterpret_cast<const char*>(uv.data()), uv.size() * 4);
    const size_t idxAt = bin.size();
    bin.append(reinterpret_cast<const char*>(idx.data()), idx.size() * 4);
    std::ofstream(dir / "grid.bin", std::ios::binary) << bin;
    const size_t nv = pos.size() / 3;
    const nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}}}}}}},
        {"buffers", {{{"byteLength", bin.size()}, {"uri", "grid.bin"}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", uvAt}},
          {{"buffer", 0}, {"byteOffset", uvAt}, {"byteLength", idxAt - uvAt}},
          {{"buffer", 0}, {"byteOffset", idxAt}, {"byteLength", bin.size() - idxAt}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"type", "VEC3"},
           {"count", nv},
           {"min", {0, 0, 0}},
           {"max", {0.5, 0.5, 0.03125}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC2"}, {"count", nv}},
          {{"bufferView", 2}, {"componentType", 5125}, {"type", "SCALAR"}, {"count", idx.size()}}}}};
    write("grid.gltf", gltf.dump());
    const CliRun a = knit("build -q --mesh grid.obj --repeats 6 6 --export yarns -o from_obj.obj", dir);
    ASSERT_EQ(a.exitCode, 0) << a.output;
    const CliRun b = knit("build -q --mesh grid.gltf --repeats 6 6 --export yarns -o from_gltf.obj", dir);
    ASSERT_EQ(b.exitCode, 0) << b.output;
    auto text = [&](const char* f) {
        std::ifstream in(dir / f);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    EXPECT_GT(text("from_gltf.obj").size(), 1000u);
    EXPECT_EQ(text("from_obj.obj"), text("from_gltf.obj"));
    // A glTF without texture coordinates: a clear error, no output.
    write("bare.gltf", R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]})");
    const CliRun c = knit("build -q --mesh bare.gltf -o never.obj", dir);
    EXPECT_EQ(c.exitCode, 1);
    EXPECT_NE(c.output.find("bare.gltf: mesh 0 primitive 0 has no TEXCOORD_0"), std::string::npos) << c.output;
    EXPECT_FALSE(fs::exists(dir / "never.obj"));
}

// Overlapping UV charts are knitted each on its own; the user is told (stderr and report), and
// both layers get the same yarns.
TEST_F(Cli, overlappingUvChartsAreReported) {
    // Two 0.1 m squares, one above the other, with the same UVs (two charts).
    write("stacked.obj",
          "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\nv 0 0 0.05\nv 0.1 0 0.05\nv 0.1 0.1 0.05\nv 0 0.1 0.05\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "f 1/1 2/2 3/3 4/4\nf 5/5 6/6 7/7 8/8\n");
    const CliRun r = knit("build -q --mesh stacked.obj --repeats 4 4 --export yarns -o y.obj --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("note: stacked.obj: UV charts overlap (0/1)"), std::string::npos) << r.output;
    std::ifstream in(dir / "r.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["mesh"]["uv_charts"].get<int>(), 2);
    EXPECT_EQ(j["mesh"]["overlapping_uv_charts"], nlohmann::json::parse("[[0, 1]]"));
    EXPECT_EQ(j["counts"]["yarns"].get<int>() % 2, 0);
    EXPECT_EQ(j["counts"]["tiles"].get<int>() % 2, 0);  // the same tiles for each of the two charts
    EXPECT_GT(j["counts"]["yarns"].get<int>(), 0);
    // A single chart: no note, an empty list.
    const CliRun p = knit("build -q --mesh plane --repeats 4 4 --export yarns -o p.obj --report p.json", dir);
    ASSERT_EQ(p.exitCode, 0) << p.output;
    EXPECT_EQ(p.output.find("note:"), std::string::npos) << p.output;
    std::ifstream pin(dir / "p.json");
    EXPECT_TRUE(nlohmann::json::parse(pin)["mesh"]["overlapping_uv_charts"].empty());
}

// A UV chart folded over itself: its folded layer gets no yarns where it lies over the rest of
// the chart, so the user is warned with the count and an example (stderr and report).
TEST_F(Cli, uvChartFoldedOverItselfIsWarnedWithCountAndExample) {
    // A strip of four 0.1 m quads whose last quad's UVs fold back over the third (u 0.75 -> 0.5).
    write("folded.obj",
          "v 0 0 0\nv 0.1 0 0\nv 0.2 0 0\nv 0.3 0 0\nv 0.4 0 0\n"
          "v 0 0.1 0\nv 0.1 0.1 0\nv 0.2 0.1 0\nv 0.3 0.1 0\nv 0.4 0.1 0\n"
          "vt 0 0\nvt 0.25 0\nvt 0.5 0\nvt 0.75 0\nvt 0.5 0\nvt 0 1\nvt 0.25 1\nvt 0.5 1\nvt 0.75 1\nvt 0.5 1\n"
          "f 1/1 2/2 7/7 6/6\nf 2/2 3/3 8/8 7/7\nf 3/3 4/4 9/9 8/8\nf 4/4 5/5 10/10 9/9\n");
    const CliRun r = knit("build -q --mesh folded.obj --repeats 8 2 --export yarns -o y.obj --report r.json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warning: folded.obj: 2 triangles fold their UV chart over itself (e.g. triangle 6 at "
                            "uv 0.75, 0)"),
              std::string::npos)
        << r.output;
    std::ifstream in(dir / "r.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["mesh"]["folded_uv_faces"].get<int>(), 2);
    EXPECT_EQ(j["mesh"]["folded_uv_face_example"].get<int>(), 6);
    // An unfolded mesh: no warning, zero folded faces.
    const CliRun p = knit("build -q --mesh plane --repeats 4 4 --export yarns -o p.obj --report p.json", dir);
    ASSERT_EQ(p.exitCode, 0) << p.output;
    EXPECT_EQ(p.output.find("warning:"), std::string::npos) << p.output;
    std::ifstream pin(dir / "p.json");
    EXPECT_EQ(nlohmann::json::parse(pin)["mesh"]["folded_uv_faces"].get<int>(), 0);
}

// Bad option values are reported by the option's name and the real cause, never by a library
// struct field or function name.
TEST_F(Cli, badOptionValuesAreNamedByTheirOptionNotByLibraryInternals) {
    const std::string base = "build -q --mesh plane --repeats 2 2 -o out.obj ";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--ply-pitch -1",
         "knit: error: the ply pitch (--ply-pitch) must be a finite length >= 0 in metres (0 = 6 yarn radii), got -1"},
        {"--ply-center-radius -0.5",
         "knit: error: the ply centre radius (--ply-center-radius) must be a finite length >= 0 in metres (0 = "
         "touching plies filling the yarn), got -0.5"},
        {"--samples-per-turn 2", "knit: error: the samples per turn (--samples-per-turn) must be in 3..1024, got 2"},
        {"--plies 1 --ply-center-radius 1",
         "knit: error: the ply radius (--ply-radius): cannot derive it for one ply with the ply centre radius "
         "(--ply-center-radius) 1 >= the yarn radius"},
    };
    for (const auto& [flags, expected] : cases) {
        const CliRun r = knit(base + flags, dir);
        EXPECT_EQ(r.exitCode, 1) << flags;
        EXPECT_NE(r.output.find(expected), std::string::npos) << flags << "\n" << r.output;
        for (const char* internal : {"PlyOptions", "ResampleOptions", "resampleYarns", "rotationMinimizingFrames"})
            EXPECT_EQ(r.output.find(internal), std::string::npos) << flags << "\n" << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.obj")) << flags;
    }
}

TEST_F(Cli, infoPrintsPatternFacts) {
    const CliRun r = knit("info " + shared("stockinette.pyp"), dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("vertices  100"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 closed loops"), std::string::npos) << r.output;
    const CliRun j = knit("info --json stockinette", dir);
    ASSERT_EQ(j.exitCode, 0) << j.output;
    EXPECT_EQ(nlohmann::json::parse(j.output)["loops_1x1"].get<int>(), 1);
}

TEST_F(Cli, everySharedPatternBuildsOnAPlane) {
    for (const char* f : {"stockinette.pyp", "stocktiny.pyp", "basket.pyp", "satin.pyp", "slip_stitch_honeycomb.pyp"}) {
        const CliRun r =
            knit(std::string("build -q --mesh plane --repeats 4 4 --pattern ") + shared(f) + " -o out.obj", dir);
        EXPECT_EQ(r.exitCode, 0) << f << ": " << r.output;
    }
}

TEST_F(Cli, malformedPatternFailsWithoutOutput) {
    write("bad.pyp", "*pattern\n1 1 0.1 2\n*Q\n0 0 0 0\n");
    const CliRun r = knit("build -q --pattern bad.pyp -o out.obj", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("bad.pyp"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST_F(Cli, meshWithoutUvsFailsWithoutOutput) {
    write("nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const CliRun r = knit("build -q --mesh nouv.obj -o out.obj --report r.json", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("nouv.obj"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.obj"));
    EXPECT_FALSE(fs::exists(dir / "r.json"));
}

TEST_F(Cli, unknownNamesAndBadFlagsFail) {
    EXPECT_NE(knit("build -q --pattern no_such_pattern -o out.obj", dir).exitCode, 0);
    EXPECT_NE(knit("build -q --mesh no_such_mesh -o out.obj", dir).exitCode, 0);
    EXPECT_NE(knit("build -q --repeats 0 5 -o out.obj", dir).exitCode, 0);
    EXPECT_NE(knit("build -q --repeats nan 5 -o out.obj", dir).exitCode, 0);
    EXPECT_NE(knit("build -q --plies 0 -o out.obj", dir).exitCode, 0);
    EXPECT_NE(knit("frobnicate", dir).exitCode, 0);
    EXPECT_EQ(fileCount(), 0u);
}

TEST_F(Cli, unwritableOutputFails) {
    const CliRun r = knit("build -q -o /nonexistent-dir/out.obj", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("/nonexistent-dir/out.obj"), std::string::npos) << r.output;
}

TEST_F(Cli, helpExplainsTheAlignment) {
    const CliRun r = knit("build --help", dir);
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.output.find("--repeats"), std::string::npos);
    EXPECT_NE(r.output.find("uv ((x + i px)/(U px)"), std::string::npos) << r.output;
}

// The scene footer ("Scene: a pattern ... tiled over a base mesh") only on commands that take a scene.
TEST_F(Cli, sceneHelpOnlyOnCommandsThatTakeAScene) {
    const std::string footer = "Scene: a pattern";
    for (const char* command : {"--help", "build --help", "animate --help", "bind --help"}) {
        const CliRun r = knit(command, dir);
        EXPECT_EQ(r.exitCode, 0) << command;
        EXPECT_NE(r.output.find(footer), std::string::npos) << command << "\n" << r.output;
    }
    for (const char* command : {"chart --help", "generate --help", "info --help", "serve --help", "strain-table --help",
                                "cache --help", "cache merge --help"}) {
        const CliRun r = knit(command, dir);
        EXPECT_EQ(r.exitCode, 0) << command;
        EXPECT_EQ(r.output.find(footer), std::string::npos) << command << "\n" << r.output;
    }
}

// An unknown subcommand is named, with the list of commands; no subcommand at all still says so.
TEST_F(Cli, unknownCommandIsNamedWithTheCommands) {
    for (const char* word : {"views", "frobnicate"}) {
        const CliRun r = knit(std::string(word) + " -o x.obj", dir);
        EXPECT_NE(r.exitCode, 0) << word;
        EXPECT_NE(r.output.find(std::string("'") + word + "' is not a knit command"), std::string::npos) << r.output;
        for (const char* command : {"build", "animate", "chart", "strain-table", "serve"})
            EXPECT_NE(r.output.find(command), std::string::npos) << command << "\n" << r.output;
        EXPECT_EQ(r.output.find("A subcommand is required"), std::string::npos) << r.output;
    }
    EXPECT_NE(knit("", dir).output.find("A subcommand is required"), std::string::npos);
    // A word under a command with subcommands of its own is named the same way.
    const CliRun nested = knit("cache frobnicate a.pc2 -o all.pc2", dir);
    EXPECT_NE(nested.exitCode, 0);
    EXPECT_NE(nested.output.find("'frobnicate' is not a knit cache command; the commands are merge"), std::string::npos)
        << nested.output;
    EXPECT_EQ(fileCount(), 0u);
}

// The generator relaxes Crane's curve to the solver's tolerance; another compiler's round-off may
// stop it elsewhere within that (far below a micrometre here), so the file is compared as numbers.
TEST_F(Cli, generateReproducesTheShippedPattern) {
    const CliRun r = knit("generate stockinette -o s.pyp", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const knit::Pattern made = knit::loadPyp((dir / "s.pyp").string()),
                        shipped = knit::loadPyp(std::string(knit::test::sourceDir()) + "/patterns/stockinette.pyp");
    ASSERT_EQ(made.points.size(), shipped.points.size());
    for (size_t i = 0; i < made.points.size(); ++i)
        EXPECT_LT(glm::length(made.points[i] - shipped.points[i]), 1e-6) << "vertex " << i;
    EXPECT_EQ(made.edges, shipped.edges);
    EXPECT_EQ(made.px, shipped.px);
    EXPECT_EQ(made.py, shipped.py);
}

}  // namespace
