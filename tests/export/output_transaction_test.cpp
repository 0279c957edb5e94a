// OutputTransaction: several outputs committed together; a failed step leaves every existing
// output byte-identical and no staging folder behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/output_transaction.hpp"
#include "test_util.hpp"

namespace {

namespace fs = std::filesystem;
using knit::OutputTransaction;
using knit::test::errorOf;
using knit::test::readText;

std::vector<std::string> namesIn(const fs::path& d) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(d)) out.push_back(fs::relative(e.path(), d).string());
    std::sort(out.begin(), out.end());
    return out;
}

void writeThrough(const std::string& staged, const std::string& text) {
    knit::writeFileAtomically(
        staged, [&](std::ostream& out) { out << text; }, false);
}

// a.txt ("old A") in the folder and b.txt in its subfolder `sub`, both staged with new contents.
struct TwoStagedOutputs {
    TwoStagedOutputs(const knit::test::TempDir& tmp, const std::string& sub)
        : a(tmp.write("a.txt", "old A")), b(tmp.file(sub + "/b.txt")) {
        fs::create_directories(tmp.path() / sub);
        writeThrough(outputs.stage(a), "new A");
        writeThrough(outputs.stage(b), "new B");
    }
    std::string a, b;
    OutputTransaction outputs;
};

TEST(OutputTransaction, failedSecondOutputLeavesTheExistingFirstUnchanged) {
    knit::test::TempDir tmp;
    const std::string a = tmp.write("a.txt", "old A"), b = tmp.write("b.txt", "old B");
    const std::string m = errorOf([&] {
        OutputTransaction outputs;
        writeThrough(outputs.stage(a), "new A");
        outputs.stage(b);
        throw knit::Error("the second output failed");
    });
    EXPECT_EQ(m, "the second output failed");
    EXPECT_EQ(readText(a), "old A");
    EXPECT_EQ(readText(b), "old B");
    EXPECT_EQ(namesIn(tmp.path()), (std::vector<std::string>{"a.txt", "b.txt"}));  // no staging folder left
}

TEST(OutputTransaction, commitReplacesEveryOutputAndRemovesTheStagingFolders) {
    knit::test::TempDir tmp;
    TwoStagedOutputs t(tmp, "sub");
    EXPECT_EQ(readText(t.a), "old A");  // nothing touched before commit
    EXPECT_FALSE(fs::exists(t.b));
    t.outputs.commit();
    EXPECT_EQ(readText(t.a), "new A");
    EXPECT_EQ(readText(t.b), "new B");
    EXPECT_EQ(namesIn(tmp.path()), (std::vector<std::string>{"a.txt", "sub", "sub/b.txt"}));
}

TEST(OutputTransaction, failedRenameRestoresTheOutputsRenamedBeforeIt) {
    knit::test::TempDir tmp;
    TwoStagedOutputs t(tmp, "second");                     // staged after a.txt: renamed after it
    fs::create_directories(fs::path(t.b) / "in-the-way");  // after staging: the rename of b must fail
    const std::string m = errorOf([&] { t.outputs.commit(); });
    EXPECT_NE(m.find("second/b.txt"), std::string::npos) << m;
    EXPECT_NE(m.find("no output was changed"), std::string::npos) << m;
    EXPECT_EQ(readText(t.a), "old A");
}

TEST(OutputTransaction, gltfBuffersAreCommittedUnderTheirFinalNames) {
    knit::test::TempDir tmp;
    knit::Polylines curves;
    const glm::dvec3 points[3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    curves.addCurve(points, 3, false);
    knit::ExportInput input;
    input.curves = &curves;
    input.radius = 0.01;
    knit::ExportOptions o;
    o.what = knit::ExportWhat::Yarns;
    OutputTransaction outputs;
    o.path = outputs.stage(tmp.file("x.gltf"));
    knit::exportCurves(input, o);
    outputs.commit();
    EXPECT_EQ(namesIn(tmp.path()), (std::vector<std::string>{"x.bin", "x.gltf"}));
    EXPECT_NE(readText(tmp.file("x.gltf")).find("\"uri\":\"x.bin\""), std::string::npos);
}

TEST(OutputTransaction, messagesNameTheFinalPathNotTheStagingFolder) {
    knit::test::TempDir tmp;
    OutputTransaction outputs;
    const std::string staged = outputs.stage(tmp.file("out.obj"));
    EXPECT_NE(staged, tmp.file("out.obj"));
    const std::string m = errorOf([&] { outputs.run([&] { throw knit::Error("cannot write '" + staged + "'"); }); });
    EXPECT_EQ(m, "cannot write '" + tmp.file("out.obj") + "'");
}

TEST(OutputTransaction, finalPathThatIsAFolderIsRefusedWhenStaged) {
    knit::test::TempDir tmp;
    fs::create_directories(tmp.path() / "out.obj");
    OutputTransaction outputs;
    EXPECT_NE(errorOf([&] { outputs.stage(tmp.file("out.obj")); }).find("a folder with that name exists"),
              std::string::npos);
}

// Two outputs of one command onto one file, by the same or another name of it: the second
// rename would silently replace the first output, so the second stage() refuses.
TEST(OutputTransaction, oneFileStagedTwiceIsRefusedUnderEitherName) {
    knit::test::TempDir tmp;
    fs::create_directories(tmp.path() / "sub");
    OutputTransaction outputs;
    outputs.stage(tmp.file("out.obj"));
    EXPECT_NE(errorOf([&] { outputs.stage(tmp.file("out.obj")); }).find("is named for two outputs"), std::string::npos);
    const std::string other = tmp.file("sub/../out.obj");
    const std::string m = errorOf([&] { outputs.stage(other); });
    EXPECT_NE(m.find("'" + other + "' is named for two outputs of this command (also as '" + tmp.file("out.obj")),
              std::string::npos)
        << m;
    EXPECT_NE(outputs.stage(tmp.file("other.obj")), "");  // another file is fine
}

}  // namespace
