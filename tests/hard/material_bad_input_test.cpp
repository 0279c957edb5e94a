// The render material file (`knit render --material FILE`) as bad input: missing, a directory,
// empty, garbage, wrong field types. Always a knit::Error naming the file, never another
// exception (the fuzz corpus in tests/fuzz_corpus/material covers the byte-level cases).
#ifdef KNIT_HARD_HAVE_RENDER_CHECK
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "knit/error.hpp"
#include "knit/ply_material.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

namespace fs = std::filesystem;

std::string materialError(const std::string& path) {
    try {
        loadMaterialFile(path);
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << path << ": non-knit exception " << e.what();
        return e.what();
    }
    ADD_FAILURE() << path << " loaded";
    return {};
}

TEST(MaterialBadInput, missingDirectoryEmptyAndGarbageFilesNameTheFile) {
    const test::TempDir tmp;
    const fs::path& dir = tmp.path();
    fs::create_directories(dir / "a_directory.json");
    std::ofstream(dir / "empty.json");
    std::ofstream(dir / "garbage.json") << "\x01\x02{{{";
    std::ofstream(dir / "wrong_type.json") << R"({"eta": [1, 2, 3]})";
    for (const char* name : {"missing.json", "a_directory.json", "empty.json", "garbage.json", "wrong_type.json"}) {
        const std::string path = (dir / name).string();
        const std::string msg = materialError(path);
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
    }
    EXPECT_NE(materialError((dir / "wrong_type.json").string()).find("eta"), std::string::npos);
}

}  // namespace
}  // namespace knit
#endif  // KNIT_HARD_HAVE_RENDER_CHECK
