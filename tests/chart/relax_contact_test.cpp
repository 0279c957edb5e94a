// The contact pair search of the relaxation (libknit/src/chart/relax_contact.hpp) against a brute
// force over every pair of segments and periodic images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/error.hpp"
#include "chart/relax_contact.hpp"

namespace knit {
namespace {

using relax::Pair;
using relax::Seg;

bool before(const Pair& a, const Pair& b) { return std::tie(a.s, a.t, a.ix, a.iy) < std::tie(b.s, b.t, b.ix, b.iy); }

// Every pair (s < t, or s == t with a positive image) within the cutoff, images up to `images`
// periods away.
std::vector<Pair> bruteForcePairs(const std::vector<glm::dvec3>& x, double px, double py, const std::vector<Seg>& segs,
                                  const relax::YarnIndex& yi, double cutoff, int images = 2) {
    std::vector<Pair> out;
    for (uint32_t s = 0; s < segs.size(); ++s)
        for (uint32_t t = s; t < segs.size(); ++t)
            for (int iy = -images; iy <= images; ++iy)
                for (int ix = -images; ix <= images; ++ix) {
                    const Pair pr{s, t, ix, iy};
                    if (t == s && (iy < 0 || (iy == 0 && ix <= 0))) continue;
                    if (relax::nearAlongYarn(yi, segs, pr, 3)) continue;
                    const glm::dvec3 p0 = x[segs[s].a],
                                     p1 = x[segs[s].b] + glm::dvec3(segs[s].dx * px, segs[s].dy * py, 0);
                    const glm::dvec3 shift(ix * px, iy * py, 0);
                    const glm::dvec3 q0 = x[segs[t].a] + shift,
                                     q1 = x[segs[t].b] + glm::dvec3(segs[t].dx * px, segs[t].dy * py, 0) + shift;
                    double a = 0, b = 0;
                    relax::closestParameters(p0, p1, q0, q1, a, b);
                    if (glm::length((p0 + a * (p1 - p0)) - (q0 + b * (q1 - q0))) <= cutoff) out.push_back(pr);
                }
    std::sort(out.begin(), out.end(), before);
    return out;
}

void expectSamePairs(std::vector<Pair> found, const std::vector<Pair>& expected) {
    std::sort(found.begin(), found.end(), before);
    ASSERT_EQ(found.size(), expected.size());
    for (size_t k = 0; k < found.size(); ++k) {
        EXPECT_EQ(found[k].s, expected[k].s);
        EXPECT_EQ(found[k].t, expected[k].t);
        EXPECT_EQ(found[k].ix, expected[k].ix);
        EXPECT_EQ(found[k].iy, expected[k].iy);
    }
}

// A cutoff wider than the period (one stitch, 7.9 x 5.6 r, against 9 r): pairs two and three
// periods apart are found too (a search of the neighbouring hash cells alone missed them).
TEST(RelaxContact, pairsBeyondTheNeighbouringPeriodsAreFound) {
    const Pattern p = chartToCell(parseChart("k\n", "k")).pattern;
    std::vector<Seg> segs(p.points.size());
    for (const PeriodicEdge& e : p.edges) segs[e.v0] = {e.v0, e.v1, e.dx, e.dy};
    const relax::YarnIndex yi = relax::indexYarns(p, segs);
    std::vector<glm::dvec3> x;
    for (const glm::dvec3& q : p.points) x.push_back(q / p.radius);
    const double px = p.px / p.radius, py = p.py / p.radius, cutoff = 9.0;
    ASSERT_LT(px, cutoff);
    const std::vector<Pair> expected = bruteForcePairs(x, px, py, segs, yi, cutoff, 4);
    ASSERT_TRUE(std::any_of(expected.begin(), expected.end(), [](const Pair& q) { return std::abs(q.iy) >= 2; }));
    expectSamePairs(relax::findPairs(x, px, py, segs, yi, cutoff), expected);
}

// The cable cell's stretched rows have legs several times longer than the other segments: they
// are listed in every hash cell their box reaches, and each pair is still found exactly once.
TEST(RelaxContact, pairsMatchBruteForceWithLongCableLegs) {
    const ChartCell cell = chartToCell(builtinChart("chart:cable4"));
    const Pattern& p = cell.pattern;
    std::vector<Seg> segs(p.points.size());
    for (const PeriodicEdge& e : p.edges) segs[e.v0] = {e.v0, e.v1, e.dx, e.dy};
    const relax::YarnIndex yi = relax::indexYarns(p, segs);
    std::vector<glm::dvec3> x;
    for (const glm::dvec3& q : p.points) x.push_back(q / p.radius);
    const double px = p.px / p.radius, py = p.py / p.radius, cutoff = 3.05;
    std::vector<Pair> found = relax::findPairs(x, px, py, segs, yi, cutoff);
    std::sort(found.begin(), found.end(), before);
    const std::vector<Pair> expected = bruteForcePairs(x, px, py, segs, yi, cutoff);
    ASSERT_FALSE(expected.empty());
    ASSERT_EQ(found.size(), expected.size());
    for (size_t k = 0; k < found.size(); ++k) {
        EXPECT_EQ(found[k].s, expected[k].s);
        EXPECT_EQ(found[k].t, expected[k].t);
        EXPECT_EQ(found[k].ix, expected[k].ix);
        EXPECT_EQ(found[k].iy, expected[k].iy);
    }
}

// An open yarn does not wrap: its first and last segments are far apart along it (an intarsia
// motif's two tails may touch), while on the same yarn closed they are neighbours.
TEST(RelaxContact, anOpenYarnsEndsAreNotNeighbours) {
    Pattern p;
    p.name = "hook";
    p.px = p.py = 50;
    p.radius = 1;
    p.points = {{0, 0, 0}, {2, 0, 0}, {4, 0, 0}, {4, 2, 0}, {2, 2, 0}, {0, 2, 0}};
    p.twist.assign(6, 0.0);
    std::vector<Seg> segs;
    for (uint32_t i = 0; i < 5; ++i) segs.push_back({i, i + 1, 0, 0});
    const relax::YarnIndex open = relax::indexYarns(p, segs, true);
    ASSERT_EQ(open.length.size(), 1u);
    EXPECT_TRUE(open.open[0]);
    EXPECT_EQ(open.length[0], 6);
    EXPECT_FALSE(relax::nearAlongYarn(open, segs, {0, 4, 0, 0}, 3));
    EXPECT_TRUE(relax::nearAlongYarn(open, segs, {0, 3, 0, 0}, 3));
    EXPECT_THROW(relax::indexYarns(p, segs), Error);  // open yarns only when asked for
    segs.push_back({5, 0, 0, 0});
    const relax::YarnIndex closed = relax::indexYarns(p, segs);
    EXPECT_FALSE(closed.open[0]);
    EXPECT_TRUE(relax::nearAlongYarn(closed, segs, {0, 4, 0, 0}, 3));
}

}  // namespace
}  // namespace knit
