#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

#include "common/fixtures.hpp"
#include "knit/error.hpp"
#include "knit/pattern.hpp"

namespace knit {
namespace {

// Undirected periodic edge in a canonical direction, in original vertex numbering.
using EdgeKey = std::tuple<uint32_t, uint32_t, int, int>;
EdgeKey canonical(uint32_t a, uint32_t b, int dx, int dy) {
    if (std::make_tuple(a, dx, dy) > std::make_tuple(b, -dx, -dy)) return {b, a, -dx, -dy};
    return {a, b, dx, dy};
}

TEST(Partners, splittingSharedPatternsAndRederivingGivesBackPeriodicEdges) {
    for (const std::string& file : test::sharedPatternFiles()) {
        const Pattern p = loadPyp(test::sharedPattern(file));
        std::vector<uint32_t> original;
        const CurveCell cell = splitAtPeriodicEdges(p, &original);
        const Pattern q = patternFromCurves(cell);
        ASSERT_EQ(q.points.size(), p.points.size()) << file;
        std::set<EdgeKey> expected, derived;
        for (const PeriodicEdge& e : p.edges)
            if (e.dx != 0 || e.dy != 0) expected.insert(canonical(e.v0, e.v1, e.dx, e.dy));
        for (const PeriodicEdge& e : q.edges)
            if (e.dx != 0 || e.dy != 0) derived.insert(canonical(original[e.v0], original[e.v1], e.dx, e.dy));
        EXPECT_EQ(expected, derived) << file;
        EXPECT_EQ(q.edges.size(), p.edges.size()) << file;
    }
}

TEST(Partners, partnersAreSymmetric) {
    for (const std::string& file : test::sharedPatternFiles()) {
        const Pattern q = patternFromCurves(splitAtPeriodicEdges(loadPyp(test::sharedPattern(file))));
        const PatternAdjacency adj = buildAdjacency(q);
        for (uint32_t v = 0; v < adj.slots.size(); ++v)
            for (const PatternNeighbor& nb : adj.slots[v]) {
                ASSERT_GE(nb.v, 0) << file << " vertex " << v << " lost a neighbour";
                const auto& back = adj.slots[nb.v];
                const bool symmetric = std::any_of(back.begin(), back.end(), [&](const PatternNeighbor& b) {
                    return b.v == int32_t(v) && b.dx == -nb.dx && b.dy == -nb.dy;
                });
                EXPECT_TRUE(symmetric) << file << " vertex " << v;
            }
    }
}

TEST(Partners, endpointWithoutPartnerIsNamed) {
    CurveCell cell;
    cell.name = "lonely.json";
    cell.px = cell.py = 1.0;
    cell.radius = 0.01;
    cell.curves = {{{0.05, 0.5, 0}, {0.5, 0.5, 0}, {0.95, 0.5, 0}},  // a course: partners itself across x
                   {{0.5, 0.1, 0}, {0.5, 0.3, 0}}};                  // a stub with no partner
    try {
        patternFromCurves(cell);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("curve 1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no partner"), std::string::npos) << e.what();
    }
}

TEST(Partners, courseCrossingTheCellJoinsItself) {
    CurveCell cell;
    cell.name = "course";
    cell.px = cell.py = 1.0;
    cell.radius = 0.05;
    cell.curves = {{{0.1, 0.5, 0}, {0.5, 0.6, 0}, {0.9, 0.5, 0}}};
    const Pattern p = patternFromCurves(cell);
    ASSERT_EQ(p.edges.size(), 3u);
    EXPECT_EQ(p.edges[2], (PeriodicEdge{2, 0, 1, 0}));
    EXPECT_EQ(describePattern(p).loops1x1, 1u);
}

TEST(Partners, curvesJsonRoundTrip) {
    const CurveCell cell = splitAtPeriodicEdges(loadPyp(test::sharedPattern("stocktiny.pyp")));
    const CurveCell back = parseCurvesJson(curvesToJson(cell), "mem.json");
    EXPECT_EQ(back.px, cell.px);
    EXPECT_EQ(back.radius, cell.radius);
    ASSERT_EQ(back.curves.size(), cell.curves.size());
    for (size_t c = 0; c < cell.curves.size(); ++c) EXPECT_EQ(back.curves[c], cell.curves[c]);
}

TEST(Partners, malformedCurvesJsonIsRejected) {
    EXPECT_THROW(parseCurvesJson("{", "a.json"), Error);
    EXPECT_THROW(parseCurvesJson("[]", "a.json"), Error);
    EXPECT_THROW(parseCurvesJson(R"({"period":[1],"radius":0.1,"curves":[[[0,0,0]]]})", "a.json"), Error);
    EXPECT_THROW(parseCurvesJson(R"({"period":[1,1],"radius":-1,"curves":[[[0,0,0]]]})", "a.json"), Error);
    EXPECT_THROW(parseCurvesJson(R"({"period":[1,1],"radius":0.1,"curves":[[[0,"x",0]]]})", "a.json"), Error);
    EXPECT_THROW(parseCurvesJson(R"({"period":[1,1],"radius":0.1})", "a.json"), Error);
    try {
        parseCurvesJson(R"({"period":[1,1],"radius":0.1,"curves":[[[0,0,0]],[[0,0]]]})", "b.json");
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("curves[1][0]"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace knit
