// `knit chart` and chart patterns on `knit build`: files written, errors with line and column.
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "chart_command.hpp"
#include "common/run_knit.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
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

// --yarn-radius sets the cell's radius, and the cell scales with it: the relaxation works in
// yarn radii (its stop tests are not exactly scale-free: measured 1.4e-4 r on the period and
// 0.011 r on the points between radius r and 3r).
TEST(ChartCommand, yarnRadiusScalesTheRelaxedCell) {
    test::TempDir dir;
    ASSERT_EQ(test::runKnit("chart chart:seed -o a.pyp", dir.path()).exitCode, 0);
    const Pattern a = loadPyp(dir.file("a.pyp"));
    const double r = 3 * a.radius;
    const test::CliRun run = test::runKnit("chart chart:seed -o b.pyp --yarn-radius " + std::to_string(r), dir.path());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const Pattern b = loadPyp(dir.file("b.pyp"));
    EXPECT_NEAR(b.radius, r, 1e-12);
    EXPECT_NEAR(b.px / b.radius, a.px / a.radius, 0.01);
    EXPECT_NEAR(b.py / b.radius, a.py / a.radius, 0.01);
    ASSERT_EQ(b.points.size(), a.points.size());
    for (size_t i = 0; i < a.points.size(); ++i) EXPECT_NEAR(b.points[i].z / b.radius, a.points[i].z / a.radius, 0.05);
    EXPECT_NE(test::runKnit("chart chart:seed -o c.pyp --yarn-radius -1", dir.path()).exitCode, 0);
    EXPECT_FALSE(std::filesystem::exists(dir.file("c.pyp")));
}

TEST(ChartCommand, badChartFailsWithLineAndColumn) {
    test::TempDir dir;
    dir.write("bad.chart", "k k\nk q\n");
    const test::CliRun r = test::runKnit("chart bad.chart -o cell.pyp", dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bad.chart:2:3: unknown stitch 'q'"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("cell.pyp")));
}

// A chart far taller than one repeat (3000 rows: a relaxation of about 15 minutes) is refused
// before relaxing, naming the file, its size and the limit, and saying to repeat one repeat.
TEST(ChartCommand, aChartTooLargeToRelaxIsRefusedBeforeTheWork) {
    test::TempDir dir;
    std::string rows;
    for (int r = 0; r < 3000; ++r) rows += "k k\n";
    dir.write("tall.chart", rows);
    const test::CliRun r = test::runKnit("chart tall.chart -o cell.pyp", dir.path());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    for (const char* words : {"tall.chart: 3000 rows x 2 stitches", "144000 yarn vertices", "more than 48000",
                              "a chart is one repeat", "--repeats"})
        EXPECT_NE(r.output.find(words), std::string::npos) << words << "\n" << r.output;
    EXPECT_EQ(r.output.find("relaxing"), std::string::npos) << r.output;  // no relaxation started
    EXPECT_FALSE(std::filesystem::exists(dir.file("cell.pyp")));
}

// The progress line of a long relaxation names the size of the cell that relaxes: a stacked
// intarsia chart (`B A B A` / `A B A B`, whose areas wander) relaxes 4 rows, its 2 rows twice over.
TEST(ChartCommand, progressLineSaysTheStackedCellsRows) {
    const Chart wander = parseChart("k k k k\nk k k k\n\nB A B A\nA B A B\nA=#ffffff B=#000000\nintarsia\n", "w.chart");
    const std::string line = cli::progressLine(wander, chartStacking(wander), 650, 4000, 10.2);
    EXPECT_EQ(line,
              "knit: relaxing w.chart (4 rows x 4 stitches: the chart's 2 rows 2 times over): iteration 650 of at "
              "most 4000, 10 s")
        << line;
    const Chart plain = parseChart("k k\nk k\nk k\n", "mid.chart");
    EXPECT_EQ(cli::progressLine(plain, chartStacking(plain), 650, 4000, 10.0),
              "knit: relaxing mid.chart (3 rows x 2 stitches): iteration 650 of at most 4000, 10 s");
}

// Stranded floats longer than --max-float (default 5) are warned about with the chart's line,
// the row and the columns, and listed in the report; the cell is written all the same.
TEST(ChartCommand, longFloatsAreWarnedAboutAndReported) {
    test::TempDir dir;
    dir.write("band.chart", "k k k k k k k\n\nA B A A A A A\nA=#ffffff B=#000000\nstranded\n");
    const test::CliRun r = test::runKnit("chart band.chart -o cell.pyp --report r.json", dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("knit: warning: band.chart:1: row 1: the float of colour B over columns 3-1 (round the "
                            "repeat) is 6 stitches long, longer than the float limit (--max-float) of 5 stitches"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("colour A over"), std::string::npos) << r.output;  // A's float is one stitch
    const std::string report = test::readText(dir.file("r.json"));
    EXPECT_NE(report.find("\"too_long\": true"), std::string::npos) << report;
    EXPECT_NE(report.find("\"max_float\": 5"), std::string::npos) << report;
    EXPECT_TRUE(std::filesystem::exists(dir.file("cell.pyp")));
    const test::CliRun quiet = test::runKnit("chart band.chart -o cell2.pyp --max-float 6", dir.path());
    ASSERT_EQ(quiet.exitCode, 0) << quiet.output;
    EXPECT_EQ(quiet.output.find("warning"), std::string::npos) << quiet.output;
    EXPECT_NE(test::runKnit("chart band.chart -o cell3.pyp --max-float 0", dir.path()).exitCode, 0);
}

// Intarsia: one yarn per colour area, no floats; a chart of odd height makes a cell of twice its
// rows (the report says both).
TEST(ChartCommand, intarsiaReportsItsYarnsAndRows) {
    test::TempDir dir;
    dir.write("ia.chart", "k k k k\n\nA A B B\nA=#ffffff B=#000000\nintarsia\n");
    const test::CliRun r = test::runKnit("chart ia.chart -o cell.pyp --report r.json", dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    const std::string report = test::readText(dir.file("r.json"));
    for (const char* field :
         {"\"yarns\": 2", "\"colourwork\": \"intarsia\"", "\"rows\": 1", "\"cell_rows\": 2", "\"floats\": []"})
        EXPECT_NE(report.find(field), std::string::npos) << field << "\n" << report;
    EXPECT_EQ(loadPyp(dir.file("cell.pyp")).rowsPerPeriod, 2);
}

// An intarsia motif's open yarns through tiling and the PLY export: every yarn (a connected
// component of the edges) keeps one colour, and the two colours are the palette's (sRGB bytes).
TEST(ChartCommand, intarsiaMotifYarnsKeepTheirColourThroughTheExport) {
    test::TempDir dir;
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);
    const test::CliRun r = test::runKnit(
        "build --pattern chart:intarsia-motif --mesh plane --repeats 2 2 --mesh-res 4 -q -o m.ply --export yarns "
        "--deform none",
        dir.path());
    ::unsetenv("KNIT_CACHE_DIR");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string text = test::readText(dir.file("m.ply"));
    size_t vertices = 0, edges = 0;
    std::istringstream header(text.substr(0, text.find("end_header\n")));
    for (std::string word; header >> word;)
        if (word == "element") {
            std::string what;
            size_t count = 0;
            header >> what >> count;
            (what == "vertex" ? vertices : edges) = count;
        }
    const size_t body = text.find("end_header\n") + 11, record = 3 * 8 + 3;
    ASSERT_EQ(text.size(), body + vertices * record + edges * 8);
    std::vector<size_t> root(vertices);
    for (size_t i = 0; i < vertices; ++i) root[i] = i;
    auto find = [&](size_t i) {
        while (root[i] != i) i = root[i] = root[root[i]];
        return i;
    };
    for (size_t e = 0; e < edges; ++e) {
        int32_t ab[2];
        std::memcpy(ab, text.data() + body + vertices * record + 8 * e, 8);
        root[find(size_t(ab[0]))] = find(size_t(ab[1]));
    }
    std::map<size_t, std::set<std::array<int, 3>>> coloursOf;
    std::set<std::array<int, 3>> all;
    for (size_t v = 0; v < vertices; ++v) {
        const char* c = text.data() + body + v * record + 24;
        const std::array<int, 3> rgb{uint8_t(c[0]), uint8_t(c[1]), uint8_t(c[2])};
        coloursOf[find(v)].insert(rgb);
        all.insert(rgb);
    }
    EXPECT_GT(coloursOf.size(), 8u);
    for (const auto& [yarn, colours] : coloursOf) EXPECT_EQ(colours.size(), 1u) << "yarn of vertex " << yarn;
    EXPECT_EQ(all, (std::set<std::array<int, 3>>{{0xf2, 0xe8, 0xd5}, {0xc1, 0x12, 0x1f}}));
}

TEST(ChartCommand, buildAcceptsAChartFileAndCachesIt) {
    test::TempDir dir;
    dir.write("seed.chart", "k p\np k\n");
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);  // the child inherits it
    // --deform none: the chart's own cache entry alone (the default would also cache its strain
    // table, made in seconds; StrainCli tests that).
    const std::string args =
        "build --pattern seed.chart --mesh plane --repeats 2 2 --mesh-res 4 -q -o y.obj --export yarns --deform none";
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
