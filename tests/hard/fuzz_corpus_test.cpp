// Replays the fuzzers' regression corpus (tests/fuzz_corpus/<parser>/, including every input
// that once crashed a parser) through the same harnesses the libFuzzer targets use
// (fuzz/fuzz_parsers.hpp): each file must either parse or raise knit::Error, nothing else. Runs
// in every build (and under ASan/UBSan via scripts/sanitize.sh), so a fixed crash stays fixed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#ifdef KNIT_HARD_HAVE_RENDER_CHECK
#define KNIT_FUZZ_HAVE_RENDER_CHECK 1
#endif
#include "../../fuzz/fuzz_parsers.hpp"
#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace knit::fuzz {
namespace {

namespace fs = std::filesystem;
using Harness = Outcome (*)(const uint8_t*, size_t);

std::vector<fs::path> corpus(const std::string& parser) {
    std::vector<fs::path> files;
    const fs::path dir = fs::path(test::sourceDir()) / "tests" / "fuzz_corpus" / parser;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// Every corpus file parses or is rejected with knit::Error; files named valid_* parse.
void replay(const std::string& parser, Harness run) {
    const std::vector<fs::path> files = corpus(parser);
    ASSERT_GE(files.size(), 5u) << "corpus for " << parser << " is missing";
    size_t parsed = 0, rejected = 0;
    for (const fs::path& f : files) {
        SCOPED_TRACE(f.string());
        const std::vector<uint8_t> data = test::readBytes(f.string());
        Outcome outcome = Outcome::Rejected;
        try {
            outcome = run(data.data(), data.size());
        } catch (const std::exception& e) {
            ADD_FAILURE() << "non-knit exception: " << e.what();
            continue;
        }
        (outcome == Outcome::Parsed ? parsed : rejected)++;
        if (f.filename().string().rfind("valid_", 0) == 0)
            EXPECT_EQ(outcome, Outcome::Parsed) << "a valid seed is rejected";
    }
    EXPECT_GT(parsed, 0u);
    EXPECT_GT(rejected, 0u);
}

TEST(FuzzCorpus, pypCorpusParsesOrThrowsKnitError) { replay("pyp", runPyp); }
TEST(FuzzCorpus, curvesJsonCorpusParsesOrThrowsKnitError) { replay("curves_json", runCurvesJson); }
TEST(FuzzCorpus, objCorpusParsesOrThrowsKnitError) { replay("obj", runObj); }
TEST(FuzzCorpus, plyCorpusParsesOrThrowsKnitError) { replay("ply", runPly); }
TEST(FuzzCorpus, offCorpusParsesOrThrowsKnitError) { replay("off", runOff); }
TEST(FuzzCorpus, boundSceneCorpusParsesOrThrowsKnitError) { replay("bound_scene", runBoundScene); }
TEST(FuzzCorpus, gltfCorpusParsesOrThrowsKnitError) { replay("gltf", runGltf); }
TEST(FuzzCorpus, strainTableCorpusParsesOrThrowsKnitError) { replay("strain_table", runStrainTable); }
TEST(FuzzCorpus, gltfAnimationCorpusParsesOrThrowsKnitError) { replay("gltf_animation", runGltfAnimation); }
TEST(FuzzCorpus, chartCorpusParsesOrThrowsKnitError) { replay("chart", runChart); }
#ifdef KNIT_FUZZ_HAVE_RENDER_CHECK
TEST(FuzzCorpus, materialCorpusParsesOrThrowsKnitError) { replay("material", runMaterial); }
#endif

}  // namespace
}  // namespace knit::fuzz
