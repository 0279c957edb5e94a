// The API's request parsing (apps/serve/src/api_request.cpp): every malformed body is refused
// with its status and a message naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "api_request.hpp"
#include "chart_job.hpp"
#include "knit/chart_cache.hpp"
#include "knit/chart_pattern.hpp"
#include "swatch.hpp"
#include "common/test_paths.hpp"

namespace knit::serve {
namespace {

// The status and message of the refusal of `parse`, or {0, ""} when it was accepted.
template <class Parse>
std::pair<int, std::string> refusal(Parse parse) {
    try {
        parse();
    } catch (const RequestError& e) {
        return {e.status(), e.what()};
    }
    return {0, ""};
}

// The page lists a chart's long floats (with their line, row and columns) and its eyelets.
TEST(ServeChart, longFloatsAndEyeletsAreWarnedAbout) {
    const auto warningsOf = [](const std::string& text) {
        const Chart chart = parsePageChart(text, 400);
        nlohmann::json w = nlohmann::json::array();
        addDesignWarnings(chart, chartToCell(chart), w);
        return w.dump();
    };
    EXPECT_EQ(warningsOf("k k k k\nk k k k\n"), "[]");
    const std::string slipped = warningsOf("k sl sl sl sl sl sl k\nk k k k k k k k\n");
    EXPECT_NE(slipped.find("line 1, row 2: the float over columns 2-7 is 6 stitches long, longer than the float "
                           "limit of 5 stitches"),
              std::string::npos)
        << slipped;
    EXPECT_EQ(warningsOf("k sl sl sl sl sl k k\nk k k k k k k k\n"), "[]");  // 5 stitches: the rule allows it
    const std::string lace = warningsOf("k yo k2tog k\nk k k k\n");
    EXPECT_NE(lace.find("1 yarn-over opens an eyelet"), std::string::npos) << lace;
}

// The preview's yarns keep as far apart as the full relaxation's (1.9 radii, the page's warning):
// its contact weight makes up for the fewer pairs of segments at 10 samples per stitch. With
// `knit chart`'s weight the preview's stockinette and seed came 1.79 radii apart, moss 1.60.
TEST(ServeChart, previewYarnsKeepApartAsInTheFullRelaxation) {
    EXPECT_DOUBLE_EQ(previewOptions().contact, RelaxOptions{}.contact * 2.4 * 2.4);
    for (const char* name : {"chart:stockinette", "chart:seed", "chart:moss"}) {
        const CellRelaxation r = relaxPageCell(builtinChart(name), previewOptions());
        EXPECT_TRUE(r.converged) << name;
        EXPECT_GE(r.minDistance, 1.9) << name;
    }
}

// The preview stops on a shorter energy window (200 iterations, 1e-5 of the decrease), still
// converged and its yarns apart: the 2 x 2 rib took 962 iterations against 1562 with `knit
// chart`'s stop test (500, 1e-6). That test is in the cache key only when changed.
TEST(ServeChart, previewStopsOnAShorterEnergyWindow) {
    const ChartPatternOptions options = previewOptions();
    EXPECT_LT(options.energyWindow, RelaxOptions{}.energyWindow);
    const CellRelaxation r = relaxPageCell(builtinChart("chart:rib1x1"), options);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(r.iterations, 1200);
    EXPECT_GE(r.minDistance, 1.9);
    const std::string chart = "k p\nk p\n";
    ChartPatternOptions defaultStop = options;
    defaultStop.energyWindow = RelaxOptions{}.energyWindow;
    defaultStop.relativeEnergyTolerance = RelaxOptions{}.relativeEnergyTolerance;
    EXPECT_NE(chartCacheKey(chart, options), chartCacheKey(chart, defaultStop));
    // `knit chart`'s key is unchanged by the stop test (as main's before it was an option; key v13,
    // issue 25 round 10: cells of up to 1500 vertices relax preconditioned).
    EXPECT_EQ(chartCacheKey(chart, {}), "chart-a94bee1269377dac.pyp");
}

// The smallest distance between two segments [p0, p1] and [q0, q1] (their closest points, each
// parameter clamped to the segment).
double segmentDistance(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0, const glm::dvec3& q1) {
    const glm::dvec3 u = p1 - p0, v = q1 - q0, w = p0 - q0;
    const double a = glm::dot(u, u), b = glm::dot(u, v), c = glm::dot(v, v), d = glm::dot(u, w), e = glm::dot(v, w);
    const double den = a * c - b * b;
    double s = den > 1e-18 ? std::clamp((b * e - c * d) / den, 0.0, 1.0) : 0.0;
    double t = c > 1e-18 ? std::clamp((b * s + e) / c, 0.0, 1.0) : 0.0;
    s = a > 1e-18 ? std::clamp((b * t - d) / a, 0.0, 1.0) : 0.0;
    return glm::length((p0 + s * u) - (q0 + t * v));
}

// The smallest distance between the centrelines of the tubes the page draws for `swatch` (its
// curves' segments: of two curves, or of one more than two segments apart), in yarn radii. Two
// open pieces' end segments are left out: a yarn cut at the swatch's edge may come back in beside
// its own cut.
double drawnMinDistance(const nlohmann::json& swatch) {
    struct Segment {
        size_t curve, index, count;
        bool end;
        glm::dvec3 a, b;
    };
    const double unit = swatch["point_unit"].get<double>(), radius = swatch["radius"].get<double>();
    std::vector<Segment> segments;
    for (size_t k = 0; k < swatch["curves"].size(); ++k) {
        const nlohmann::json& c = swatch["curves"][k];
        const std::vector<double> x = c["points"].get<std::vector<double>>();
        const size_t n = x.size() / 3, count = c["closed"].get<bool>() ? n : n - 1;
        const auto at = [&](size_t i) {
            return unit * glm::dvec3(x[3 * (i % n)], x[3 * (i % n) + 1], x[3 * (i % n) + 2]);
        };
        for (size_t i = 0; i < count; ++i)
            segments.push_back({k, i, count, !c["closed"].get<bool>() && (i == 0 || i + 1 == count), at(i), at(i + 1)});
    }
    double closest = 1e9;
    for (size_t i = 0; i < segments.size(); ++i)
        for (size_t j = i + 1; j < segments.size(); ++j) {
            const Segment &s = segments[i], &t = segments[j];
            if (glm::length(0.5 * (s.a + s.b - t.a - t.b)) > 6 * radius) continue;
            if (s.curve == t.curve) {
                const size_t gap = t.index - s.index;
                if (std::min(gap, s.count - gap) <= 2) continue;
            } else if (s.end && t.end) {
                continue;
            }
            closest = std::min(closest, segmentDistance(s.a, s.b, t.a, t.b));
        }
    return closest / radius;
}

// What the page draws of the preview keeps the yarns apart too: the swatch places the relaxed
// cell's own points (no resampling), so its tubes come as close as the relaxation's segments.
TEST(ServeChart, previewSwatchDrawsTheYarnsApart) {
    const Chart chart = builtinChart("chart:moss");
    const ChartPatternOptions options = previewOptions();
    const ChartCell cell = chartToCell(chart, cellOptions(options));
    const CellRelaxation r = relaxPageCell(chart, options);
    const double drawn = drawnMinDistance(swatchJson(relaxedChart(chart, cell, r).pattern, {0, 0}));
    EXPECT_GE(drawn, 1.9);
    EXPECT_NEAR(drawn, r.minDistance, 0.01);
}

// The swatch's points and colours are integers in their units (micrometres, thousandths): points
// in metres, rounded to a micrometre, came as doubles such as -0.034402999999999996 (the JSON
// library writes 17 digits), twice the bytes for the page to load.
TEST(ServeChart, swatchPointsAndColoursAreIntegers) {
    const Chart chart = parsePageChart("k p\np k\n\nA B\nB A\nA=#c8553d B=#2a6f97\n", 400);
    const ChartPatternOptions options = previewOptions();
    const ChartCell cell = chartToCell(chart, cellOptions(options));
    const RelaxedChart relaxed = relaxedChart(chart, cell, relaxPageCell(chart, options));
    const nlohmann::json swatch = swatchJson(relaxed.pattern, {0, 0});
    EXPECT_EQ(swatch["point_unit"], 1e-6);
    EXPECT_EQ(swatch["colour_unit"], 1e-3);
    ASSERT_TRUE(swatch["curves"][0].contains("colours"));
    const std::string text = swatch["curves"].dump();
    EXPECT_EQ(text.find('.'), std::string::npos) << text.substr(0, 200);
    // The swatch is centred on the plane: points within half its side.
    const double half = 0.5 * swatch["size"].get<double>() / 1e-6;
    for (const nlohmann::json& c : swatch["curves"])
        for (const nlohmann::json& x : c["points"]) EXPECT_LE(std::abs(x.get<double>()), half * 1.01);
}

// A relaxation depends on the chart's cell, not its text: a comment or colour edit keeps its key
// (the server does not relax it again) and the chart made from the other text's relaxation is
// exactly relaxChart's; another stitch, stranded colours or the preview's samples change the key.
TEST(ServeChart, aColourOrCommentEditReusesTheCellsRelaxation) {
    const ChartPatternOptions options;
    const auto keyOf = [](const std::string& text, const ChartPatternOptions& o) {
        return relaxationKey(chartToCell(parsePageChart(text, 400), cellOptions(o)), o);
    };
    const std::string plain = "k p\nk p\n";
    const std::string coloured = "# striped\nk p\nk p\n\nA A\nB B\nA=#c8553d B=#2a6f97\n";
    EXPECT_EQ(keyOf(plain, options), keyOf(coloured, options));
    EXPECT_NE(keyOf(plain, options), keyOf("k p\np k\n", options));
    EXPECT_NE(keyOf("k k\nk k\n", options), keyOf("k k\nk k\n\nA B\nA B\nA=#c8553d B=#2a6f97\nstranded\n", options));
    ChartPatternOptions preview = options;
    preview.samplesPerStitch = 10;
    EXPECT_NE(keyOf(plain, options), keyOf(plain, preview));
    // The preview relaxes by plain L-BFGS; the solver is in the key too.
    EXPECT_FALSE(previewOptions().hessianPreconditioner);
    EXPECT_NE(keyOf(plain, previewOptions()), keyOf(plain, preview));

    const Chart chart = parsePageChart(coloured, 400);
    const RelaxedChart reused = relaxedChart(chart, chartToCell(chart, cellOptions(options)),
                                             relaxPageCell(parsePageChart(plain, 400), options));
    const Pattern direct = relaxChart(chart, options).relaxed.pattern;
    ASSERT_FALSE(direct.colour.empty());
    EXPECT_EQ(reused.pattern.points, direct.points);
    EXPECT_EQ(reused.pattern.colour, direct.colour);
    EXPECT_EQ(reused.pattern.twist, direct.twist);
    EXPECT_EQ(reused.pattern.edges.size(), direct.edges.size());
    EXPECT_EQ(reused.pattern.px, direct.px);
    EXPECT_EQ(reused.pattern.py, direct.py);
    EXPECT_EQ(reused.stats["samples_per_stitch"], 24);
}

TEST(ServeRequest, swatchRequestIsParsed) {
    const SwatchRequest r = parseSwatchRequest(R"({"session":"abc-1","chart":"k k\nk k\n","repeats":[3,4]})", {});
    EXPECT_EQ(r.session, "abc-1");
    EXPECT_EQ(r.chart, "k k\nk k\n");
    EXPECT_EQ(r.repeats[0], 3);
    EXPECT_EQ(r.repeats[1], 4);
}

TEST(ServeRequest, malformedBodiesAreRefusedNamingTheField) {
    const RequestLimits limits;
    const auto swatch = [&](const std::string& body) { return refusal([&] { parseSwatchRequest(body, limits); }); };
    EXPECT_EQ(swatch("{"), std::make_pair(400, std::string("the request body is not valid JSON")));
    EXPECT_EQ(swatch("[1]").first, 400);
    EXPECT_EQ(swatch(R"({"chart":"k"})").second, "\"session\" must be a string (the page's id)");
    EXPECT_EQ(swatch(R"({"session":"a b","chart":"k"})").second,
              "\"session\" may hold only letters, digits, '-' and '_'");
    EXPECT_EQ(swatch(R"({"session":"a"})").second, "\"chart\" must be a string (the chart text)");
    EXPECT_EQ(swatch(R"({"session":"a","chart":"k","colour":1})").second, "unknown field \"colour\"");
    EXPECT_EQ(swatch(R"({"session":"a","chart":"k","repeats":[0,5]})").first, 400);
    EXPECT_EQ(swatch(R"({"session":"a","chart":"k","repeats":[1,1e9]})").first, 400);
    EXPECT_EQ(swatch(R"({"session":"a","chart":"k","repeats":"3"})").first, 400);
    EXPECT_EQ(swatch(R"({"session":"a","chart":"k","repeats":[1,1]})").first, 0);
}

TEST(ServeRequest, chartOverTheSizeLimitIs413) {
    RequestLimits limits;
    limits.maxChartBytes = 10;
    const auto [status, message] =
        refusal([&] { parseSwatchRequest(R"({"session":"a","chart":"k k k k k k"})", limits); });
    EXPECT_EQ(status, 413);
    EXPECT_EQ(message, "\"chart\" is 11 bytes, over the limit of 10");
}

TEST(ServeRequest, garmentViewGaugeAndFormatAreChecked) {
    const RequestLimits limits;
    const GarmentRequest g = parseGarmentRequest(
        R"({"session":"a","chart":"k","mesh":"plane","gauge":"22x30/10cm",
            "view":{"eye":[0,1,1],"target":[0,0,0],"up":[0,1,0],"fov":40,"width":640,"height":480}})",
        limits, false);
    ASSERT_TRUE(g.gauge);
    EXPECT_DOUBLE_EQ(g.gauge->stitches, 22);
    ASSERT_TRUE(g.view);
    EXPECT_EQ(g.view->width, 640);
    EXPECT_EQ(g.mesh, "plane");
    const auto garment = [&](const std::string& body, bool download) {
        return refusal([&] { parseGarmentRequest(body, limits, download); });
    };
    EXPECT_EQ(garment(R"({"session":"a","chart":"k","repeats":[2,2],"gauge":"22x30/10cm"})", false).second,
              "give \"repeats\" or \"gauge\", not both");
    EXPECT_EQ(garment(R"({"session":"a","chart":"k","gauge":"lots"})", false).first, 400);
    EXPECT_EQ(garment(R"({"session":"a","chart":"k","view":{"eye":[0,0,0],"target":[0,0,0]}})", false).first, 400);
    EXPECT_EQ(
        garment(R"({"session":"a","chart":"k","view":{"eye":[0,0,1],"target":[0,0,0],"width":1.5}})", false).first,
        400);
    EXPECT_EQ(garment(R"({"session":"a","chart":"k","format":"glb"})", false).second, "unknown field \"format\"");
    EXPECT_EQ(garment(R"({"session":"a","chart":"k","format":"obj"})", true).second,
              "\"format\" must be \"pyp\", \"glb\" or \"pc2\"");
    EXPECT_EQ(parseGarmentRequest(R"({"session":"a","chart":"k","format":"pc2"})", limits, true).format,
              DownloadFormat::Pc2);
}

// The fuzzer's regression corpus (fuzz/serve_request_fuzzer.cpp), replayed in every build: each
// body is accepted or refused with 400 / 413, and a parsed chart fails only at a line and column.
TEST(ServeRequest, fuzzCorpusIsAcceptedOrRefusedAsBadRequest) {
    const std::filesystem::path folder = std::string(test::sourceDir()) + "/tests/fuzz_corpus/serve_request";
    RequestLimits limits;
    limits.maxChartStitches = 64;
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        const std::string body = bytes.str();
        ++files;
        for (int endpoint = 0; endpoint < 4; ++endpoint) {
            const auto [status, message] = refusal([&] {
                if (endpoint == 0) {
                    const SwatchRequest r = parseSwatchRequest(body, limits);
                    try {
                        parsePageChart(r.chart, limits.maxChartStitches);
                    } catch (const ChartTextError& e) {
                        EXPECT_GE(e.line(), 1) << entry.path();
                        EXPECT_GE(e.column(), 1) << entry.path();
                    }
                }
                if (endpoint == 1) parseGarmentRequest(body, limits, false);
                if (endpoint == 2) parseGarmentRequest(body, limits, true);
                if (endpoint == 3) parseCancelRequest(body);
            });
            EXPECT_TRUE(status == 0 || status == 400 || status == 413)
                << entry.path() << ": " << status << " " << message;
        }
    }
    EXPECT_GE(files, 4u);
}

}  // namespace
}  // namespace knit::serve
