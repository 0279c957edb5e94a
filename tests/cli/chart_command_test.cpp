// `knit chart` and chart patterns on `knit build`: files written, errors with line and column.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iterator>

#include "common/run_knit.hpp"
#include "knit/pattern.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

TEST(ChartCommand, writesARelaxedCellAndAReport) {
    test::TempDir dir;
    const test::CliRun r = test::runKnit("chart chart:stockinette -o cell.pyp --report r.json", dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Pattern p = loadPyp(dir.file("cell.pyp"));
    EXPECT_EQ(p.points.size(), 96u);
    EXPECT_NE(test::readText(dir.file("r.json")).find("\"min_distance_radii\""), std::string::npos);
}

TEST(ChartCommand, badChartFailsWithLineAndColumn) {
    test::TempDir dir;
    dir.write("bad.chart", "k k\nk q\n");
    const test::CliRun r = test::runKnit("chart bad.chart -o cell.pyp", dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bad.chart:2:3: unknown stitch 'q'"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("cell.pyp")));
}

TEST(ChartCommand, buildAcceptsAChartFileAndCachesIt) {
    test::TempDir dir;
    dir.write("seed.chart", "k p\np k\n");
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);  // the child inherits it
    const std::string args =
        "build --pattern seed.chart --mesh plane --repeats 2 2 --mesh-res 4 -q -o y.obj --export yarns";
    const test::CliRun r = test::runKnit(args, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("y.obj")));
    EXPECT_EQ(
        std::distance(std::filesystem::directory_iterator(dir.file("cache")), std::filesystem::directory_iterator()),
        1);
    ::unsetenv("KNIT_CACHE_DIR");
}

}  // namespace
}  // namespace knit
