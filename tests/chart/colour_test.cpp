// A chart's colour layer through the pipeline: per-vertex colour in the pattern (and its .pyp
// block), the tiled and stitched yarns, the binding, the mapped yarns and the plies.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>

#include "knit/base_mesh.hpp"
#include "knit/chart.hpp"
#include "knit/chart_cache.hpp"
#include "knit/chart_topology.hpp"
#include "knit/error.hpp"
#include "knit/pattern.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

const glm::vec3 kRed(1.f, 0.f, 0.f), kBlue(0.f, 0.f, 1.f);

// Two rows: the bottom one red (A), the top one blue (B).
const char* kStripes = "k k\nk k\n\nB B\nA A\nA=#ff0000 B=#0000ff\n";

std::string pypError(const std::string& text) {
    std::istringstream in(text);
    try {
        parsePyp(in, "c.pyp");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string chartError(const std::string& text) {
    try {
        parseChart(text, "bad.chart");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(Colour, badColourRowsAndPaletteEntriesNameLineAndColumn) {
    EXPECT_EQ(chartError("k k\n\nA\nA=#000000\n"), "bad.chart:3:1: colour row has 1 letters, expected 2");
    EXPECT_EQ(chartError("k k\n\nA AB\nA=#000000\n"), "bad.chart:3:3: colour 'AB' is not one letter");
    EXPECT_EQ(chartError("k\n\nA\nA=#000000 A=#ffffff\n"), "bad.chart:4:11: colour 'A' is defined twice");
    EXPECT_EQ(chartError("k\n\nA\n"), "bad.chart:3:1: colour 'A' is not in the palette");
    EXPECT_EQ(chartError("k\n\nA\nA=#12345\n"), "bad.chart:4:1: palette entry 'A=#12345' is not LETTER=#rrggbb");
}

TEST(Colour, stripeChartColoursEveryVertexOfARowWithItsLinearColour) {
    const ChartCell cell = chartToCell(parseChart(kStripes, "stripes.chart"));
    const Pattern& p = cell.pattern;
    ASSERT_EQ(p.colour.size(), p.points.size());
    for (const StitchLoop& l : cell.loops)
        for (uint32_t i = l.first; i < l.first + l.count; ++i)
            ASSERT_EQ(p.colour[i], l.row == 0 ? kRed : kBlue) << "vertex " << i << " row " << l.row;
}

TEST(Colour, paletteIsConvertedFromSrgbToLinear) {
    const ChartCell cell = chartToCell(parseChart("k\n\nA\nA=#808080\n", "grey.chart"));
    // sRGB 128/255 = 0.50196 is linear ((0.50196 + 0.055) / 1.055)^2.4 = 0.21586.
    EXPECT_NEAR(cell.pattern.colour.front().r, 0.21586f, 1e-5f);
}

TEST(Colour, duplicateStitchColoursOnlyItsOwnLoop) {
    const ChartCell cell = chartToCell(parseChart("k k k\nk k k\n\nA A A\nA B A\nA=#ffffff B=#0000ff\n", "dup.chart"));
    for (const StitchLoop& l : cell.loops) {
        const bool dot = l.row == 0 && l.column == 1;
        for (uint32_t i = l.first; i < l.first + l.count; ++i)
            ASSERT_EQ(cell.pattern.colour[i], dot ? kBlue : glm::vec3(1.f)) << l.row << "," << l.column;
    }
}

TEST(Colour, pypColourBlockRoundTripsAndFilesWithoutItHaveNone) {
    const Pattern p = chartToCell(parseChart(kStripes, "stripes.chart")).pattern;
    std::ostringstream out;
    writePyp(out, p);
    EXPECT_NE(out.str().find("\n*RGB"), std::string::npos);
    std::istringstream in(out.str());
    const Pattern q = parsePyp(in, "stripes.pyp");
    EXPECT_EQ(q.colour, p.colour);
    EXPECT_TRUE(q.extraBlocks.empty());

    Pattern plain = p;
    plain.colour.clear();
    std::ostringstream out2;
    writePyp(out2, plain);
    EXPECT_EQ(out2.str().find("*RGB"), std::string::npos);
    std::istringstream in2(out2.str());
    EXPECT_TRUE(parsePyp(in2, "plain.pyp").colour.empty());
}

TEST(Colour, pypColourBlockWithWrongRowsOrRangeFailsWithLine) {
    const std::string head = "*pattern\n1 1 0.1 2\n*Q\n0 0 0 0\n0.5 0 0 0\n*E\n0 1 0 0\n1 0 1 0\n";
    EXPECT_EQ(pypError(head + "*RGB\n1 0 0\n"), "c.pyp:9: *RGB has 1 rows but *pattern declares 2 vertices");
    EXPECT_EQ(pypError(head + "*RGB\n1 0 0\n0 0 2\n"), "c.pyp:11: *RGB colour components must be in [0, 1]");
    EXPECT_EQ(pypError(head + "*RGB\n1 0 0\n0 0\n"), "c.pyp:11: *RGB row has 2 values, expected 3");
}

TEST(Colour, chartCacheKeyChangesWithTheColourLayer) {
    EXPECT_NE(chartCacheKey(kStripes, {}), chartCacheKey("k k\nk k\n\nA A\nB B\nA=#ff0000 B=#0000ff\n", {}));
    EXPECT_NE(chartCacheKey(kStripes, {}), chartCacheKey("k k\nk k\n", {}));
}

// The stripe cell (unrelaxed: the colours do not depend on the shape) on a plane.
Scene stripeScene(bool plies) {
    SceneOptions o;
    o.placement.repeats = {3, 3};
    o.buildPlies = plies;
    return buildScene(chartToCell(parseChart(kStripes, "stripes.chart")).pattern, makePlane(), o);
}

TEST(Colour, stitchedYarnVerticesTakeTheColourOfTheirPatternVertex) {
    const Scene scene = stripeScene(false);
    const Pattern& p = scene.pattern();
    const UvYarns& uv = scene.stages().uvYarns;
    ASSERT_EQ(uv.colour.size(), uv.vertexCount());
    for (size_t i = 0; i < uv.vertexCount(); ++i)
        ASSERT_EQ(uv.colour[i], p.colour[uv.source[i] % p.points.size()]) << i;
}

TEST(Colour, stripeRowsAlternateColourOnTheMappedYarns) {
    const Scene scene = stripeScene(false);
    const MappedYarns& y = scene.yarns();
    ASSERT_EQ(y.colour.size(), y.curves.pointCount());
    ASSERT_EQ(scene.binding().colour.size(), scene.binding().vertexCount());
    // Each yarn is one course: one colour. Sorted across the courses (plane: z runs along v),
    // the colours alternate red, blue, red, ...
    // Whole courses only (the loops poking in over the v boundary are cut into short pieces).
    uint32_t longest = 0;
    for (size_t c = 0; c < y.curves.curveCount(); ++c) longest = std::max(longest, y.curves.size(c));
    std::vector<std::pair<double, glm::vec3>> courses;
    for (size_t c = 0; c < y.curves.curveCount(); ++c) {
        if (2 * y.curves.size(c) < longest) continue;
        double z = 0;
        for (uint32_t i = y.curves.begin(c); i < y.curves.end(c); ++i) {
            ASSERT_EQ(y.colour[i], y.colour[y.curves.begin(c)]) << "yarn " << c << " changes colour";
            z += y.curves.points[i].z;
        }
        courses.emplace_back(z / y.curves.size(c), y.colour[y.curves.begin(c)]);
    }
    std::sort(courses.begin(), courses.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    ASSERT_GE(courses.size(), 4u);
    for (size_t k = 1; k < courses.size(); ++k) {
        EXPECT_TRUE(courses[k].second == kRed || courses[k].second == kBlue);
        EXPECT_NE(courses[k].second, courses[k - 1].second) << "courses " << k - 1 << " and " << k;
    }
}

TEST(Colour, everyPlyPointHasItsYarnsColour) {
    const Scene scene = stripeScene(true);
    const Plies& pl = scene.plies();
    const MappedYarns& y = scene.yarns();
    ASSERT_EQ(pl.colour.size(), pl.curves.pointCount());
    for (size_t c = 0; c < pl.curves.curveCount(); ++c) {
        const glm::vec3 yarn = y.colour[y.curves.begin(pl.yarnOfCurve[c])];
        for (uint32_t i = pl.curves.begin(c); i < pl.curves.end(c); ++i) ASSERT_EQ(pl.colour[i], yarn) << c;
    }
}

TEST(Colour, duplicateStitchChangesColourWithinTheCourse) {
    SceneOptions o;
    o.placement.repeats = {2, 2};
    o.buildPlies = true;
    const Pattern p =
        chartToCell(parseChart("k k k\nk k k\n\nA A A\nA B A\nA=#ffffff B=#0000ff\n", "dup.chart")).pattern;
    const Scene scene = buildScene(p, makePlane(), o);
    const Plies& pl = scene.plies();
    // Some ply curve holds both colours (the blue stitch within a white course).
    bool mixed = false;
    for (size_t c = 0; c < pl.curves.curveCount() && !mixed; ++c) {
        std::map<float, int> seen;
        for (uint32_t i = pl.curves.begin(c); i < pl.curves.end(c); ++i) ++seen[pl.colour[i].r];
        mixed = seen.size() == 2;
    }
    EXPECT_TRUE(mixed);
}

// Stranded colourwork: every yarn is one colour, through the pattern, the mapped yarns and the
// plies (the exports and the renderer read these arrays), and both colours are knitted.
TEST(Colour, strandedYarnsKeepTheirColourThroughThePipeline) {
    const Pattern p = chartToCell(builtinChart("chart:fair-isle")).pattern;
    SceneOptions o;
    o.placement.repeats = {2, 2};
    o.buildPlies = true;
    const Scene scene = buildScene(p, makePlane(), o);
    const MappedYarns& y = scene.yarns();
    ASSERT_EQ(y.colour.size(), y.curves.pointCount());
    std::map<float, int> colours;  // by red component: cream and navy differ there
    for (size_t c = 0; c < y.curves.curveCount(); ++c) {
        for (uint32_t i = y.curves.begin(c); i < y.curves.end(c); ++i)
            ASSERT_EQ(y.colour[i], y.colour[y.curves.begin(c)]) << "yarn " << c << " changes colour";
        ++colours[y.colour[y.curves.begin(c)].r];
    }
    EXPECT_EQ(colours.size(), 2u);
    const Plies& pl = scene.plies();
    ASSERT_EQ(pl.colour.size(), pl.curves.pointCount());
    for (size_t c = 0; c < pl.curves.curveCount(); ++c)
        for (uint32_t i = pl.curves.begin(c); i < pl.curves.end(c); ++i)
            ASSERT_EQ(pl.colour[i], y.colour[y.curves.begin(pl.yarnOfCurve[c])]) << c;
}

TEST(Colour, patternsWithoutColoursCarryNoColourArrays) {
    SceneOptions o;
    o.placement.repeats = {3, 3};
    const Scene scene = buildScene(chartToCell(parseChart("k k\nk k\n", "plain.chart")).pattern, makePlane(), o);
    EXPECT_TRUE(scene.pattern().colour.empty());
    EXPECT_TRUE(scene.stages().uvYarns.colour.empty());
    EXPECT_TRUE(scene.binding().colour.empty());
    EXPECT_TRUE(scene.yarns().colour.empty());
    EXPECT_TRUE(scene.plies().colour.empty());
}

}  // namespace
}  // namespace knit
