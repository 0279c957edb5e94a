// Issue 25 constructs after relaxation: the new built-ins relax apart and keep their crossings,
// an eyelet stays open, stranded floats stay behind the stitches they pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <map>

#include "crossings.hpp"
#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"
#include "openings.hpp"
#include "common/test_paths.hpp"

namespace knit {
namespace {

using test::Crossing;

// Each chart relaxed once per process.
const ChartPattern& relaxed(const std::string& text, const std::string& name) {
    static std::map<std::string, ChartPattern> done;
    auto it = done.find(text);
    if (it == done.end()) it = done.emplace(text, relaxChart(parseChart(text, name))).first;
    return it->second;
}
const ChartPattern& relaxedBuiltin(const std::string& name) { return relaxed(builtinChartText(name), name); }

ChartCell relaxedCell(const ChartPattern& cp) {
    ChartCell c = cp.cell;
    c.pattern = cp.relaxed.pattern;
    return c;
}

glm::dvec3 centre(const Pattern& p, const StitchLoop& l) {
    glm::dvec3 c(0.0);
    for (uint32_t i = l.first; i < l.first + l.count; ++i) c += p.points[i];
    return c / double(l.count);
}

// After relaxation, seen along the stitch's own normal (course x wale, as test::stitchFrame):
// the highest crossing of a stitch with each loop it is pulled through has the new loop in front
// for knit, behind for purl (its legs over the head). "" or what is wrong.
std::string checkThroughEnds(const ChartCell& cell, const StitchLoop& l) {
    const Pattern& p = cell.pattern;
    const std::string where = "stitch (" + std::to_string(l.row) + ", " + std::to_string(l.column) + ")";
    for (const LoopRef& ref : l.through) {
        const StitchLoop& b = cell.loop(ref.row, ref.column);
        const int iy = ref.row >= l.row ? -1 : 0;
        const glm::dvec3 cl = centre(p, l), cb = centre(p, b);
        const glm::dvec3 shift(-std::round((cb.x - cl.x) / p.px) * p.px, iy * p.py, 0);
        const glm::dvec3 wale = glm::normalize(cl - (cb + shift));
        const glm::dvec3 course = p.points[l.first + l.count - 1] - p.points[l.first];
        test::Frame f;
        f.n = glm::normalize(glm::cross(course, wale));
        f.e2 = glm::normalize(wale - glm::dot(wale, f.n) * f.n);
        f.e1 = glm::cross(f.e2, f.n);
        std::vector<Crossing> c =
            test::crossingsBetween(p, l.first, l.first + l.count, b.first, b.first + b.count, iy, f);
        if (c.empty()) return where + ": no crossing with a loop it is pulled through";
        std::sort(c.begin(), c.end(), [](const Crossing& x, const Crossing& y) { return x.at.y < y.at.y; });
        if ((c.back().at.z > c.back().zb) != (l.kind == StitchKind::Knit))
            return where + ": its legs are on the wrong side of the head of (" + std::to_string(ref.row) + ", " +
                   std::to_string(ref.column) + ")";
    }
    return "";
}

void expectNewBuiltinsRelaxApartWithTheirCrossings() {
    for (const char* name : {"chart:eyelet-mesh", "chart:honeycomb", "chart:fishermans-rib", "chart:fair-isle"}) {
        const ChartPattern& cp = relaxedBuiltin(name);
        std::printf("%-22s %4d iterations %.2f s, min distance %.3f r, period %.2f x %.2f r\n", name,
                    cp.relaxed.iterations, cp.seconds, cp.relaxed.minDistance,
                    cp.relaxed.pattern.px / cp.relaxed.pattern.radius,
                    cp.relaxed.pattern.py / cp.relaxed.pattern.radius);
        EXPECT_GE(cp.relaxed.minDistance, 1.9) << name;
        EXPECT_GT(cp.relaxed.closestApproach, 0.2) << name;
        const ChartCell cell = relaxedCell(cp);
        for (const StitchLoop& l : cell.loops)
            if (l.madeLoop) EXPECT_EQ(checkThroughEnds(cell, l), "") << name;
    }
}

// An eyelet's largest empty disc seen along z, beyond the yarn surfaces, against plain knitting's.
void expectEyeletOpen() {
    const test::Opening plain = test::largestOpening(relaxedBuiltin("chart:stockinette").relaxed.pattern);
    const ChartPattern& lace = relaxedBuiltin("chart:eyelet-mesh");
    const test::Opening eyelet = test::largestOpening(lace.relaxed.pattern);
    std::printf("largest opening: stockinette %.2f r, eyelet mesh %.2f r\n", plain.radius, eyelet.radius);
    EXPECT_GE(eyelet.radius, 1.5);
    EXPECT_GE(eyelet.radius, 1.5 * plain.radius);
}

// Yarn length per area (L r / A) of the slip-stitch honeycomb against the HYLC honeycomb cell.
void expectHoneycombDensityNearHylc() {
    auto lengthPerArea = [](const Pattern& p) {
        double L = 0;
        for (const PeriodicEdge& e : p.edges)
            L += glm::length(p.points[e.v1] + glm::dvec3(e.dx * p.px, e.dy * p.py, 0) - p.points[e.v0]);
        return L * p.radius / (p.px * p.py);
    };
    const Pattern hylc = loadPyp(std::string(test::sharedDir()) + "/patterns/hylc/slip_stitch_honeycomb.pyp");
    const double ours = lengthPerArea(relaxedBuiltin("chart:honeycomb").relaxed.pattern), theirs = lengthPerArea(hylc);
    std::printf("L r / A: honeycomb %.3f, HYLC slip-stitch honeycomb %.3f\n", ours, theirs);
    EXPECT_NEAR(ours / theirs, 1.0, 0.15);
}

// Stranded floats stay on the wrong side after relaxation: behind every stitch they cross, and
// the front of the stranded band stands no further out than the same chart in one yarn per row.
void expectStrandedFloatsBehind() {
    const std::string text = builtinChartText("chart:fair-isle");
    const std::string oneYarn = text.substr(0, text.rfind("stranded\n"));
    const ChartPattern &two = relaxedBuiltin("chart:fair-isle"), &one = relaxed(oneYarn, "one-yarn");
    const ChartCell cell = relaxedCell(two);
    const Pattern& p = cell.pattern;
    std::vector<bool> inLoop(p.points.size(), false);
    for (const StitchLoop& l : cell.loops)
        for (uint32_t i = l.first; l.madeLoop && i < l.first + l.count; ++i) inLoop[i] = true;
    int crossings = 0;
    ASSERT_FALSE(cell.floats.empty());
    for (const ChartFloat& f : cell.floats)
        for (uint32_t v : f.vertices)
            for (int iy = -1; iy <= 1; ++iy)
                for (const Crossing& x : test::crossingsBetween(p, v, v + 1, 0, uint32_t(p.points.size()), iy))
                    if (inLoop[x.b] && std::abs(int(x.b) - int(v)) > 2) {
                        EXPECT_LT(x.at.z, x.zb) << "a float of row " << f.row << " passes in front of a stitch";
                        ++crossings;
                    }
    EXPECT_GT(crossings, 0);
    auto front = [](const Pattern& q) {
        double z = -1e300;
        for (const glm::dvec3& v : q.points) z = std::max(z, v.z);
        return z / q.radius;
    };
    auto back = [](const Pattern& q) {
        double z = 1e300;
        for (const glm::dvec3& v : q.points) z = std::min(z, v.z);
        return z / q.radius;
    };
    std::printf(
        "front / back: stranded %.2f / %.2f r, one yarn %.2f / %.2f r; period %.2f x %.2f r, one yarn %.2f x %.2f r\n",
        front(two.relaxed.pattern), back(two.relaxed.pattern), front(one.relaxed.pattern), back(one.relaxed.pattern),
        two.relaxed.pattern.px / p.radius, two.relaxed.pattern.py / p.radius, one.relaxed.pattern.px / p.radius,
        one.relaxed.pattern.py / p.radius);
    EXPECT_LE(front(two.relaxed.pattern), front(one.relaxed.pattern) + 0.1);
}

// One test, so each chart is relaxed once (ctest runs every test in its own process): the new
// built-ins relax apart and keep their crossings; the eyelet stays open; the honeycomb's density
// is near HYLC's; stranded floats stay behind.
TEST(ChartConstructsRelaxed, roundTwoBuiltinsAfterRelaxation) {
    expectNewBuiltinsRelaxApartWithTheirCrossings();
    expectEyeletOpen();
    expectHoneycombDensityNearHylc();
    expectStrandedFloatsBehind();
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

// A loop held on three rows draws extra yarn from its neighbours (chart_topology.cpp,
// kThirdRowYarn): with a plain loop's length it pulled the rows so tight that the yarns came to
// 1.868 r apart.
TEST(ChartConstructsRelaxed, loopsHeldThreeRowsKeepTheYarnsApart) {
    for (const char* text : {"k k\nk sl\nk sl\nk sl\n", "k k\nk tuck\nk tuck\nk tuck\n"}) {
        const ChartPattern cp = relaxChart(parseChart(text, "held.chart"));
        std::string label(text);
        std::replace(label.begin(), label.end(), '\n', '/');
        std::printf("%-32s min distance %.3f r, %d iterations\n", label.c_str(), cp.relaxed.minDistance,
                    cp.relaxed.iterations);
        EXPECT_GE(cp.relaxed.minDistance, 1.9) << text;
        EXPECT_GT(cp.relaxed.closestApproach, 0.2) << text;
    }
}

}  // namespace
}  // namespace knit
