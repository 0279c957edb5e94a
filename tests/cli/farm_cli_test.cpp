// Farm bakes end to end (issue 26): `knit bind` once, `knit animate --bound --first A --last B`
// per chunk, `knit cache merge`: the same bytes as one `knit animate` run, whatever the chunks,
// with the deformation `knit bind` chose as `knit animate` chooses it (the file carries it, with
// the strain table whole). The chunking tests bind and animate with --deform none (no table).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "animate_sequence.hpp"
#include "common/run_knit.hpp"

namespace fs = std::filesystem;

namespace knit::test {
namespace {

std::string bytesOf(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Farm : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("knit_farm_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        writeWaveSequence(dir, 9, 8);
    }
    void TearDown() override { fs::remove_all(dir); }
    CliRun knit(const std::string& args) const { return runKnit(args, dir); }
    void bind(const std::string& deform = "--deform none") const {
        const CliRun r = knit("bind -q --mesh frame_0001.obj --repeats 3 3 " + deform + " -o g.knitbind");
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    // `animate --bound` over frames first..last into `out`.
    void chunk(int first, int last, const std::string& out, const std::string& more = "") const {
        const CliRun r = knit("animate -q --bound g.knitbind --frames frame_%04d.obj --first " + std::to_string(first) +
                              " --last " + std::to_string(last) + " " + more + " -o " + out);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    fs::path dir;
};

TEST_F(Farm, chunksOfABoundSceneMergeToTheBytesOfOneRun) {
    bind();
    CliRun r = knit("animate -q --frames frame_%04d.obj --repeats 3 3 --deform none -o one.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string one = bytesOf(dir / "one.pc2"), topology = bytesOf(dir / "one.obj");
    ASSERT_GT(one.size(), 9 * 12 * 1000u);
    // 1, 2 and 3 chunks (given out of order), merged.
    const std::vector<std::vector<std::pair<int, int>>> splits = {{{1, 9}}, {{5, 9}, {1, 4}}, {{7, 9}, {1, 3}, {4, 6}}};
    for (size_t s = 0; s < splits.size(); ++s) {
        std::string chunks;
        for (const auto& [a, b] : splits[s]) {
            const std::string name = "s" + std::to_string(s) + "_" + std::to_string(a) + ".pc2";
            chunk(a, b, name);
            chunks += name + " ";
        }
        const std::string merged = "m" + std::to_string(s) + ".pc2";
        r = knit("cache merge " + chunks + "-o " + merged);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("frames 1-9"), std::string::npos) << r.output;
        EXPECT_TRUE(bytesOf(dir / merged) == one) << splits[s].size() << " chunks";
        EXPECT_TRUE(bytesOf(dir / ("m" + std::to_string(s) + ".obj")) == topology) << splits[s].size() << " chunks";
    }
    // MDD and per-frame files of a chunk: the single run's frames.
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 3 --deform none -o one.mdd");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    chunk(1, 9, "bound.mdd");
    EXPECT_TRUE(bytesOf(dir / "bound.mdd") == bytesOf(dir / "one.mdd"));
    // MDD chunks (no start frame in MDD: each chunk's .obj records its frames and rate) merge
    // to the single run's MDD and .obj.
    chunk(6, 9, "mdd_6.mdd");
    chunk(1, 5, "mdd_1.mdd");
    r = knit("cache merge mdd_6.mdd mdd_1.mdd -o mdd.mdd");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frames 1-9"), std::string::npos) << r.output;
    EXPECT_TRUE(bytesOf(dir / "mdd.mdd") == bytesOf(dir / "one.mdd"));
    EXPECT_TRUE(bytesOf(dir / "mdd.obj") == bytesOf(dir / "one.obj"));
    EXPECT_NE(bytesOf(dir / "mdd_6.obj").find("MDD frames 6-9 step 1 at 24 fps\n"), std::string::npos);
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 3 --deform none --export yarns -o one_%04d.obj");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    chunk(4, 6, "part_%04d.obj", "--export yarns");
    for (const char* k : {"0004", "0005", "0006"})
        EXPECT_TRUE(bytesOf(dir / (std::string("part_") + k + ".obj")) ==
                    bytesOf(dir / (std::string("one_") + k + ".obj")))
            << k;
    EXPECT_FALSE(fs::exists(dir / "part_0003.obj"));
    // With a frame step the chunks record it (the PC2 sample rate) and merge the same way.
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 3 --deform none --step 2 -o two.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    chunk(1, 5, "t1.pc2", "--step 2");
    chunk(7, 9, "t2.pc2", "--step 2");
    r = knit("cache merge t1.pc2 t2.pc2 -o t.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(bytesOf(dir / "t.pc2") == bytesOf(dir / "two.pc2"));
}

TEST_F(Farm, mergeNamesMissingAndDoubledFramesAndWritesNothing) {
    bind();
    chunk(1, 3, "a.pc2");
    chunk(4, 6, "b.pc2");
    chunk(5, 9, "c.pc2");
    chunk(8, 9, "d.pc2");
    CliRun r = knit("cache merge a.pc2 d.pc2 -o m.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("frames 4-7 missing (between 'a.pc2' and 'd.pc2')"), std::string::npos) << r.output;
    r = knit("cache merge a.pc2 b.pc2 c.pc2 -o m.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("frames 5-6 in both 'b.pc2' and 'c.pc2'"), std::string::npos) << r.output;
    r = knit("cache merge a.pc2 b.pc2 b.pc2 -o m.pc2");
    EXPECT_NE(r.output.find("frames 4-6 in both 'b.pc2' and 'b.pc2'"), std::string::npos) << r.output;
    // A chunk of another garment (3 plies): not the same points.
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 3 --deform none --plies 3 --first 7 --last 9 -o e.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = knit("cache merge a.pc2 b.pc2 e.pc2 -o m.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("differ"), std::string::npos) << r.output;
    // A truncated chunk.
    fs::resize_file(dir / "b.pc2", fs::file_size(dir / "b.pc2") - 12);
    r = knit("cache merge a.pc2 b.pc2 -o m.pc2");
    EXPECT_NE(r.output.find("point cache 'b.pc2' has"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(truncated)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "m.pc2"));
    EXPECT_FALSE(fs::exists(dir / "m.obj"));
    // MDD chunks: a gap named the same way; chunks of another format refused.
    chunk(1, 3, "a.mdd");
    chunk(6, 9, "f.mdd");
    r = knit("cache merge a.mdd f.mdd -o m.mdd");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("frames 4-5 missing (between 'a.mdd' and 'f.mdd')"), std::string::npos) << r.output;
    r = knit("cache merge a.mdd a.pc2 -o m.mdd");
    EXPECT_NE(r.output.find("point cache 'a.pc2' is not an MDD (.mdd) like 'm.mdd'"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "m.mdd"));
}

TEST_F(Farm, boundFileErrorsNameTheFileAndTheFlag) {
    bind();
    CliRun r = knit("animate -q --bound g.knitbind --pattern rib --frames frame_%04d.obj -o c.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("--pattern cannot be given with --bound"), std::string::npos) << r.output;
    fs::resize_file(dir / "g.knitbind", fs::file_size(dir / "g.knitbind") / 2);
    r = knit("animate -q --bound g.knitbind --frames frame_%04d.obj -o c.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bound scene 'g.knitbind' is truncated"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "c.pc2"));
    // A frame of another mesh is refused naming the frame.
    writeWaveFrame(dir / "other_0001.obj", 1, 5);
    r = knit("bind -q --mesh frame_0001.obj --repeats 3 3 --deform none -o g.knitbind");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = knit("animate -q --bound g.knitbind --frames other_%04d.obj -o c.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("frame 1"), std::string::npos) << r.output;
}

// `knit bind` makes the deform decision `knit animate` makes (the same flags, the same default:
// knit::decideDeform) and the file carries it with the strain table whole, so a farm worker
// without the cache deforms the frames as one `knit animate` run does, byte for byte; with
// --deform none too. Repeats of 3 x 5 on the square strain the layout (the wave, the frames).
TEST_F(Farm, aBoundSceneDeformsItsFramesAsOneAnimateRunDoes) {
    CliRun r = knit("bind --mesh frame_0001.obj --repeats 3 5 -o s.knitbind");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("(deform: strain, its table embedded: "), std::string::npos) << r.output;
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 5 -o one.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ::setenv("KNIT_CACHE_DIR", (dir / "worker_cache").c_str(), 1);  // a worker without the cache
    r = knit("animate -q --bound s.knitbind --frames frame_%04d.obj --report b.json -o bound.pc2");
    ::unsetenv("KNIT_CACHE_DIR");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string one = bytesOf(dir / "one.pc2");
    ASSERT_GT(one.size(), 9 * 12 * 1000u);
    EXPECT_TRUE(bytesOf(dir / "bound.pc2") == one);
    EXPECT_TRUE(bytesOf(dir / "bound.obj") == bytesOf(dir / "one.obj"));
    EXPECT_FALSE(fs::exists(dir / "worker_cache"));  // nothing looked up or made there
    const nlohmann::json report = nlohmann::json::parse(bytesOf(dir / "b.json"));
    EXPECT_EQ(report["deform"]["mode"], "strain");
    EXPECT_EQ(report["deform"]["why"].get<std::string>().rfind("as bound (knit bind): ", 0), 0u) << report["deform"];
    // --deform none on both: geometric frames, the same bytes, and not the strain-aware ones.
    r = knit("bind -q --mesh frame_0001.obj --repeats 3 5 --deform none -o n.knitbind");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = knit("animate -q --frames frame_%04d.obj --repeats 3 5 --deform none -o one_none.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = knit("animate -q --bound n.knitbind --frames frame_%04d.obj -o bound_none.pc2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(bytesOf(dir / "bound_none.pc2") == bytesOf(dir / "one_none.pc2"));
    EXPECT_FALSE(bytesOf(dir / "bound_none.pc2") == one);
    EXPECT_GT(fs::file_size(dir / "s.knitbind"), fs::file_size(dir / "n.knitbind") + 200000);  // the table
    // A damaged table (the last field of the file) is refused naming the file; nothing is written.
    std::string damaged = bytesOf(dir / "s.knitbind");
    damaged[damaged.size() - 3] ^= 0x20;
    std::ofstream(dir / "s.knitbind", std::ios::binary | std::ios::trunc) << damaged;
    r = knit("animate -q --bound s.knitbind --frames frame_%04d.obj -o c.pc2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bound scene 's.knitbind' is damaged: its checksum does not match"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "c.pc2"));
}

#ifdef KNIT_HAVE_RENDER_CHECK
// With the default deformation on both sides: the bound scene renders as the single run does.
TEST_F(Farm, renderOfABoundSceneSkipsBindingAndPosesItAsAnimate) {
    bind("");
    const std::string size = " --width 48 --height 36 --spp 2";
    CliRun r = knit("render -q --mesh frame_0001.obj --repeats 3 3 --detail full" + size + " --output full.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = knit("render -q --bound g.knitbind" + size + " --output rest.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(bytesOf(dir / "rest.png") == bytesOf(dir / "full.png"));  // the rest pose: the same image
    for (const char* out : {"f5a.png", "f5b.png"}) {
        r = knit("render -q --bound g.knitbind --frame-mesh frame_0005.obj" + size + " --output " + out);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    EXPECT_TRUE(bytesOf(dir / "f5a.png") == bytesOf(dir / "f5b.png"));
    EXPECT_FALSE(bytesOf(dir / "f5a.png") == bytesOf(dir / "rest.png"));
    r = knit("render -q --bound g.knitbind --detail view --output x.png");
    EXPECT_NE(r.output.find("--detail view cannot be given with --bound"), std::string::npos) << r.output;
    r = knit("render -q --frame-mesh frame_0005.obj --output x.png");
    EXPECT_NE(r.output.find("--frame-mesh needs --bound"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}
#endif

}  // namespace
}  // namespace knit::test
