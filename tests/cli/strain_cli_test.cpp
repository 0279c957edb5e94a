// `knit strain-table`, `knit info T.npy` and the --deform / --strain-table scene flags: the table
// file numpy reads, the report's deform section, refusals naming the table, and an interrupted
// table run that leaves no file.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "common/run_knit.hpp"
#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace knit {
namespace {

namespace fs = std::filesystem;

// A small table of the default pattern (3 x 2 x 3 samples), made once per test folder.
std::string smallTable(const test::TempDir& dir) {
    const test::CliRun r = test::runKnit("strain-table --samples 3 2 3 --sx-range -0.1 0.6 -o t.npy", dir.path());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("estimated"), std::string::npos) << r.output;  // the estimate comes first
    return dir.file("t.npy");
}

TEST(StrainCli, strainTableWritesATableInfoDescribes) {
    const test::TempDir dir;
    smallTable(dir);
    EXPECT_TRUE(fs::exists(dir.file("t.axes.txt")));
    const test::CliRun info = test::runKnit("info t.npy --json", dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.output;
    const nlohmann::json j = nlohmann::json::parse(info.output);
    EXPECT_EQ(j["vertices"], 24);
    EXPECT_EQ(j["samples"], nlohmann::json({3, 2, 3}));
    EXPECT_EQ(j["pattern"]["name"], "stockinette");
    EXPECT_GT(j["largest_displacement"].get<double>(), 0.0);
    EXPECT_EQ(j["largest_twist"].get<double>(), 0.0);  // the project's own tables have no twist
}

TEST(StrainCli, buildReportsTheDeformModeAndTable) {
    const test::TempDir dir;
    smallTable(dir);
    // Repeats that stretch the pattern along u: a strained layout (sx ~ 0.4 against v).
    const std::string scene = "build --mesh plane --mesh-res 8 --repeats 30 60 --export yarns ";
    const test::CliRun s = test::runKnit(scene + "--strain-table t.npy -o s.obj --report s.json", dir.path());
    ASSERT_EQ(s.exitCode, 0) << s.output;
    const nlohmann::json rs = nlohmann::json::parse(test::readText(dir.file("s.json")));
    EXPECT_EQ(rs["deform"]["mode"], "strain");
    EXPECT_EQ(rs["deform"]["strain_table"], "t.npy");
    EXPECT_EQ(rs["deform"]["samples"], nlohmann::json({3, 2, 3}));
    EXPECT_GT(rs["deform"]["displaced_vertices"].get<size_t>(), 0U);
    EXPECT_EQ(rs["deform"]["why"], "--strain-table given");
    const test::CliRun g = test::runKnit(scene + "--deform none -o g.obj --report g.json", dir.path());
    ASSERT_EQ(g.exitCode, 0) << g.output;
    const nlohmann::json rg = nlohmann::json::parse(test::readText(dir.file("g.json")));
    EXPECT_EQ(rg["deform"]["mode"], "none");
    EXPECT_EQ(rg["deform"]["why"], "--deform none");
    EXPECT_NE(test::readText(dir.file("s.obj")), test::readText(dir.file("g.obj")));
    // --deform none with a table given: the geometric mapping, as without one.
    const test::CliRun n = test::runKnit(scene + "--deform none --strain-table t.npy -o n.obj -q", dir.path());
    ASSERT_EQ(n.exitCode, 0) << n.output;
    EXPECT_EQ(test::readText(dir.file("n.obj")), test::readText(dir.file("g.obj")));
}

// The default (no --deform) for the default pattern is strain: its table is made on first use
// (seconds) and cached, then read from the cache (--deform strain reads the same entry), and the
// yarns are the same either way. The report says which mode ran and why.
TEST(StrainCli, defaultDeformMakesCachesAndReadsThePatternsTable) {
    const test::TempDir dir;
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);  // the child inherits it
    const std::string scene = "build --mesh plane --mesh-res 4 --repeats 10 20 --export yarns ";
    const test::CliRun a = test::runKnit(scene + "-o a.obj --report a.json", dir.path());
    const test::CliRun b = test::runKnit(scene + "--deform strain -o b.obj", dir.path());
    const test::CliRun c = test::runKnit(scene + "-o c.obj --report c.json", dir.path());
    ::unsetenv("KNIT_CACHE_DIR");
    ASSERT_EQ(a.exitCode, 0) << a.output;
    ASSERT_EQ(b.exitCode, 0) << b.output;
    ASSERT_EQ(c.exitCode, 0) << c.output;
    EXPECT_NE(a.output.find("deform: strain (made the pattern's strain table in"), std::string::npos) << a.output;
    EXPECT_NE(b.output.find("strain table from the cache"), std::string::npos) << b.output;
    const nlohmann::json ra = nlohmann::json::parse(test::readText(dir.file("a.json")));
    const nlohmann::json rc = nlohmann::json::parse(test::readText(dir.file("c.json")));
    EXPECT_EQ(ra["deform"]["mode"], "strain");
    EXPECT_NE(ra["deform"]["why"].get<std::string>().find("made now"), std::string::npos) << ra["deform"];
    EXPECT_EQ(rc["deform"]["why"], "the pattern's strain table was in the cache");
    EXPECT_GT(rc["deform"]["displaced_vertices"].get<size_t>(), 0U);  // --repeats 10 20 strains the layout
    EXPECT_EQ(test::readText(dir.file("a.obj")), test::readText(dir.file("c.obj")));
    EXPECT_EQ(b.output.find("strain samples"), std::string::npos) << b.output;  // not made again
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(dir.file("cache")))
        entries += e.path().filename().string().rfind("strain-", 0) == 0 ? 1 : 0;
    EXPECT_EQ(entries, 2U);  // T.npy and T.axes.txt
    EXPECT_EQ(test::readText(dir.file("a.obj")), test::readText(dir.file("b.obj")));
}

// A pattern whose table would take a minute or more (120 cell vertices): the default is none, with
// a note naming the command that makes the table and its estimated time; nothing is made.
TEST(StrainCli, defaultDeformIsNoneWhereMakingTheTableIsSlow) {
    const test::TempDir dir;
    ASSERT_EQ(test::runKnit("generate stockinette --samples 120 -o big.pyp", dir.path()).exitCode, 0);
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);
    const test::CliRun r =
        test::runKnit("build --pattern big.pyp --mesh plane --mesh-res 2 --repeats 2 4 --export yarns -o b.obj "
                      "--report b.json",
                      dir.path());
    ::unsetenv("KNIT_CACHE_DIR");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("deform: none"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("`knit strain-table --pattern big.pyp -o T.npy`"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("takes about"), std::string::npos) << r.output;
    const nlohmann::json j = nlohmann::json::parse(test::readText(dir.file("b.json")));
    EXPECT_EQ(j["deform"]["mode"], "none");
    EXPECT_NE(j["deform"]["why"].get<std::string>().find("no strain table at hand"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir.file("cache")) && !fs::is_empty(dir.file("cache")));
}

TEST(StrainCli, mismatchedOrDamagedTablesAreRefusedNamingThem) {
    const test::TempDir dir;
    smallTable(dir);
    const std::string pattern = std::string(test::sharedDir()) + "/patterns/hylc/stocktiny.pyp";
    const test::CliRun m =
        test::runKnit("build -q --mesh plane --pattern '" + pattern + "' --strain-table t.npy -o m.obj", dir.path());
    EXPECT_NE(m.exitCode, 0);
    EXPECT_NE(m.output.find("t.npy"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("cell vertices"), std::string::npos) << m.output;
    EXPECT_FALSE(fs::exists(dir.file("m.obj")));
    dir.write("bad.npy", "\x93NUMPY garbage");
    dir.write("bad.axes.txt", "0\n0\n0\n");
    const test::CliRun b = test::runKnit("build -q --mesh plane --strain-table bad.npy -o b.obj", dir.path());
    EXPECT_NE(b.exitCode, 0);
    EXPECT_NE(b.output.find("bad.npy"), std::string::npos) << b.output;
    const test::CliRun d = test::runKnit("build -q --mesh plane --deform sideways -o d.obj", dir.path());
    EXPECT_NE(d.exitCode, 0);
    EXPECT_NE(d.output.find("--deform"), std::string::npos) << d.output;
}

// Ctrl-C while the samples relax: no table, no axes file, no temporary file.
TEST(StrainCli, interruptedTableRunLeavesNoFile) {
    const test::TempDir dir;
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (::chdir(dir.path().c_str()) != 0) ::_exit(127);
        ::execl(test::knitCli(), test::knitCli(), "strain-table", "-q", "--samples", "40", "40", "40", "-o", "t.npy",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    ::kill(pid, SIGINT);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
    for (const auto& e : fs::directory_iterator(dir.path())) ADD_FAILURE() << "left behind: " << e.path();
}

}  // namespace
}  // namespace knit
