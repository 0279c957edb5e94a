// Geometry of the three tracing modes on hand-made plies: far ray origins, sharp joints, open
// ends, grazing rays on tubes, what each mode gives TraceScene (trace_geometry.hpp), and the
// fiber texture phase of closed loops.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/plies.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/synthetic_scene.hpp"
#include "tracing/trace_geometry.hpp"
#include "tracing/trace_scene.hpp"

namespace knit {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPlyRadius = 0.001;  // metres; scene units are ply radii

// Plies made of the given open or closed polylines (in ply radii), radial = +z.
Plies handMadePlies(const std::vector<std::vector<glm::dvec3>>& curves, bool closed = false) {
    Plies p;
    p.plyRadius = kPlyRadius;
    for (const auto& c : curves) {
        std::vector<glm::dvec3> metres;
        for (const glm::dvec3& q : c) metres.push_back(q * kPlyRadius);
        p.curves.addCurve(metres.data(), metres.size(), closed);
        p.yarnOfCurve.push_back(0);
        p.plyOfCurve.push_back(0);
        p.radial.insert(p.radial.end(), c.size(), glm::dvec3(0, 0, 1));
    }
    return p;
}

TraceSceneOptions modeOptions(GeometryMode mode, const std::vector<int64_t>& cells, int sides = 16) {
    TraceSceneOptions o;
    o.mode = mode;
    o.tubeSides = sides;
    o.segmentCells = &cells;  // one cell for everything (grid mode)
    return o;
}

// Distance from p to the axis of segment s, in ply radii.
float axisDistance(const PlyGeometry& g, uint32_t s, const glm::vec3& p) {
    const uint32_t j = g.segments[s];
    const glm::vec3 a(g.points[j]), b(g.points[j + 1]);
    const float t = glm::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.f, 1.f);
    return glm::length(a + t * (b - a) - p) / g.radius;
}

TEST(TraceScene, gridHitsStayOnThePlySurfaceFromDistantOrigins) {
    // `knit render` puts the camera ~3000 ply radii from the drape. The ray-cylinder test in float
    // cancelled catastrophically from there (hits up to 0.6 radii off the surface, a 3.5% darker
    // grid image); it must be as exact as from nearby.
    SyntheticSceneOptions so;
    so.courses = 5;
    so.yarnRadius = 0.0008;
    so.plyCount = 3;
    so.waveAmplitude = 0.0004;
    so.cellSize = 0.25;
    const Scene scene = makeSyntheticPlyScene(so);
    const PlyGeometry g = buildPlyGeometry(scene.plies(), glm::dvec3(0.005, 0.005, 0));
    const std::vector<int64_t> cells = segmentCells(scene, g);
    EmbreeDevice device;
    const TraceScene curves(device, g, modeOptions(GeometryMode::Curves, cells));
    const TraceScene grid(device, g, modeOptions(GeometryMode::Grid, cells));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(-0.004, 0.004), angle(0, 2 * kPi);
    int both = 0, onSurface = 0, agree = 0, onlyOne = 0;
    for (int i = 0; i < 4000; ++i) {
        // Origins 3000-6000 ply radii away (1.1-2.2 m for this 0.37 mm ply radius).
        const double dist = (3000 + 3000 * (i % 7) / 6.0) * g.unit, a = angle(rng);
        const glm::dvec3 target = g.origin + glm::dvec3(uni(rng), uni(rng), 0.0);
        const glm::dvec3 from = target + dist * glm::normalize(glm::dvec3(0.5 * std::cos(a), 0.5 * std::sin(a), 1.0));
        const glm::vec3 org = g.toScene(from), dir = glm::normalize(g.toScene(target) - org);
        TraceHit hc, hg;
        const bool c = curves.intersect(org, dir, 0.f, 1e30f, hc), gr = grid.intersect(org, dir, 0.f, 1e30f, hg);
        onlyOne += c != gr;
        if (!c || !gr) continue;
        ++both;
        const float d = axisDistance(g, hg.segment, org + hg.t * dir);
        onSurface += d > 0.995f && d < 1.01f;
        agree += std::abs(hc.t - hg.t) < 0.02f;
    }
    EXPECT_GT(both, 2000);
    EXPECT_GT(onSurface, 0.99 * both);
    EXPECT_GT(agree, 0.99 * both);
    EXPECT_LT(onlyOne, 0.01 * both);
}

TEST(TraceScene, jointBentBeyondMitreLimitIsRoundInGridMode) {
    // A 170-degree hairpin: too sharp to mitre (the mitre would reach 11 radii out). Cutting both
    // segments flat left the outside of the bend open; the grid must show the round joint that
    // Embree's round curves have.
    const double bend = 170.0 * kPi / 180.0;
    const glm::dvec3 back(-std::cos(kPi - bend) * 10.0, std::sin(kPi - bend) * 10.0, 0.0);
    const Plies plies = handMadePlies({{{-20, 0, 0}, {-10, 0, 0}, {0, 0, 0}, back, back + glm::dvec3(-10, 0, 0)}});
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0));
    const std::vector<int64_t> cells(g.segmentCount(), 0);
    EmbreeDevice device;
    const TraceScene curves(device, g, modeOptions(GeometryMode::Curves, cells));
    const TraceScene grid(device, g, modeOptions(GeometryMode::Grid, cells));
    int rays = 0, matched = 0;
    for (int iy = -8; iy <= 8; ++iy)
        for (int iz = -8; iz <= 8; ++iz) {
            // At the outside of the bend; not exactly along the axis (Embree's round curves miss
            // rays exactly parallel to a segment).
            const glm::vec3 org(5.f, 0.1f * iy, 0.1f * iz), dir = glm::normalize(glm::vec3(-1.f, 0.013f, 0.017f));
            if (glm::length(glm::vec2(org.y, org.z)) > 0.9f) continue;
            ++rays;
            TraceHit hc, hg;
            ASSERT_TRUE(curves.intersect(org, dir, 0.f, 1e30f, hc));
            if (grid.intersect(org, dir, 0.f, 1e30f, hg) && std::abs(hg.t - hc.t) < 2e-3f) {
                ++matched;
                EXPECT_GT(glm::dot(hg.ng, -dir), 0.f);  // an entering hit with an outward normal
            }
        }
    EXPECT_GT(rays, 150);
    EXPECT_EQ(matched, rays);
}

TEST(TraceScene, openEndsAreRoundInEveryMode) {
    // Embree's round curves end in a half sphere; the grid cells and the tubes (whose exported
    // flat caps are replaced) must end the same way, or the images differ at every yarn end.
    const Plies plies = handMadePlies({{{0, 0, 0}, {4, 0, 0}, {8, 0.5, 0}, {12, 0, 0}}});
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0));
    const std::vector<int64_t> cells(g.segmentCount(), 0);
    EmbreeDevice device;
    const TraceScene curves(device, g, modeOptions(GeometryMode::Curves, cells));
    const int sides = 32;
    const float polygonError = 1.f - std::cos(float(kPi) / sides);  // of the inscribed tube polygon
    for (GeometryMode mode : {GeometryMode::Grid, GeometryMode::Tubes}) {
        const TraceScene other(device, g, modeOptions(mode, cells, sides));
        for (int end = 0; end < 2; ++end)
            for (int k = 0; k < 40; ++k) {
                // Rays nearly along the axis into each end (not exactly: Embree's round curves
                // miss rays exactly parallel to a segment), off the axis by up to 0.8 radii.
                const float a = 0.7f * k, rho = 0.8f * k / 39.f;
                const glm::vec3 off(0.f, rho * std::cos(a), rho * std::sin(a));
                const glm::vec3 centre = end ? glm::vec3(12, 0, 0) : glm::vec3(0.f);
                const glm::vec3 org = centre + off + glm::vec3(end ? 5.f : -5.f, 0.f, 0.f);
                const glm::vec3 dir = glm::normalize(glm::vec3(end ? -1.f : 1.f, 0.004f, -0.003f));
                TraceHit hc, ho;
                ASSERT_TRUE(curves.intersect(org, dir, 0.f, 1e30f, hc));
                ASSERT_TRUE(other.intersect(org, dir, 0.f, 1e30f, ho)) << modeName(mode);
                // The end sphere of radius 1.
                const float b = glm::dot(org - centre, dir), c = glm::dot(org - centre, org - centre) - 1.f;
                EXPECT_NEAR(hc.t, -b - std::sqrt(b * b - c), 2e-3f);
                const float cosIncidence = std::sqrt(std::max(0.04f, 1.f - rho * rho));
                const float tolerance = mode == GeometryMode::Tubes ? 2.f * polygonError / cosIncidence : 2e-3f;
                EXPECT_NEAR(ho.t, hc.t, tolerance) << modeName(mode) << " end " << end << " rho " << rho;
                EXPECT_EQ(ho.segment, hc.segment) << modeName(mode);
            }
    }
}

TEST(TraceScene, tubeIsEnteredFromBothSidesOfEveryChord) {
    // A tube is a closed polyhedron: a line through it is entered whichever way it is traversed.
    // Lines that clip a corner of the polygon beyond the inscribed radius enter the facet while
    // moving away from the axis; deciding "entering" by the centreline normal (not the facet's)
    // dropped those entries one way round, so the ray passed through the tube.
    const Plies plies = handMadePlies({{{0, 0, 0}, {10, 0, 0}, {20, 0, 0}, {30, 0, 0}}});
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0));
    const std::vector<int64_t> cells(g.segmentCount(), 0);
    EmbreeDevice device;
    const int sides = 6;
    const TraceScene tubes(device, g, modeOptions(GeometryMode::Tubes, cells, sides));
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    const float inscribed = std::cos(float(kPi) / sides);
    int lines = 0, oneWay = 0, chords = 0;
    for (int i = 0; i < 20000; ++i) {
        // A line passing the axis at distance in (inscribed, 1): through corners or missing.
        const float phi = 2 * float(kPi) * uni(rng), d = inscribed + (1.f - inscribed) * uni(rng);
        const glm::vec3 radial(0.f, std::cos(phi), std::sin(phi)), tangent(0.f, -std::sin(phi), std::cos(phi));
        const glm::vec3 foot = glm::vec3(8.f + 14.f * uni(rng), 0.f, 0.f) + d * radial;
        const glm::vec3 dir = glm::normalize(tangent + 0.2f * (uni(rng) - 0.5f) * glm::vec3(1, 0, 0));
        TraceHit fwd, bwd;
        const bool f = tubes.intersect(foot - 4.f * dir, dir, 0.f, 8.f, fwd);
        const bool b = tubes.intersect(foot + 4.f * dir, -dir, 0.f, 8.f, bwd);
        ++lines;
        oneWay += f != b;
        if (f && b) {
            ++chords;
            EXPECT_LE(fwd.t + bwd.t, 8.f + 1e-3f);  // the two entries are the chord's two ends
        }
    }
    EXPECT_GT(chords, 1000);
    EXPECT_EQ(oneWay, 0) << "of " << lines << " lines";
}

TEST(TraceGeometry, factoryRejectsTooFewTubeSidesAndMissingGridCells) {
    // Each mode checks its own options when it is built, with the messages `knit render` shows.
    const Plies plies = handMadePlies({{{0, 0, 0}, {4, 0, 0}, {8, 0.5, 0}, {12, 0, 0}}});
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0));
    const std::vector<int64_t> cells(g.segmentCount(), 0), tooFew(g.segmentCount() - 1, 0);
    auto errorOf = [&](const TraceSceneOptions& o) -> std::string {
        try {
            makeTraceGeometry(g, o);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(errorOf(modeOptions(GeometryMode::Tubes, cells, 2)), "cannot render: tube sides must be >= 3");
    EXPECT_EQ(errorOf(modeOptions(GeometryMode::Tubes, cells, 3)), "");
    const std::string noCells = "cannot render: grid mode needs a UV-grid cell for every ply segment";
    EXPECT_EQ(errorOf(modeOptions(GeometryMode::Grid, tooFew)), noCells);
    TraceSceneOptions none = modeOptions(GeometryMode::Grid, cells);
    none.segmentCells = nullptr;
    EXPECT_EQ(errorOf(none), noCells);
    EXPECT_EQ(errorOf(modeOptions(GeometryMode::Curves, tooFew)), "");  // curves use no cells
    // TraceScene passes them on unchanged.
    EmbreeDevice device;
    try {
        const TraceScene scene(device, g, modeOptions(GeometryMode::Tubes, cells, 2));
        ADD_FAILURE() << "tube sides 2 accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "cannot render: tube sides must be >= 3");
    }
}

TEST(TraceGeometry, eachModeReportsItsPrimitivesAndSpawnRules) {
    // What TraceScene takes from a mode: primitive count and bytes for the report, the primitive a
    // spawned ray ignores (only tubes: the facet it leaves) and the inscribed radius transmitted
    // rays start within (the tube polygon's; 1 for the round solids).
    const Plies plies =
        handMadePlies({{{0, 0, 0}, {4, 0, 0}, {8, 0.5, 0}, {12, 0, 0}, {16, 0, 0}}, {{0, 5, 0}, {4, 5, 0}, {8, 5, 0}}});
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0));
    std::vector<int64_t> cells(g.segmentCount());
    for (size_t s = 0; s < cells.size(); ++s) cells[s] = static_cast<int64_t>(s / 2);  // two per cell
    const size_t cellCount = (g.segmentCount() + 1) / 2;
    TraceHit from;
    from.kind = TraceHit::Ply;
    from.primID = 7;
    const int sides = 6;
    EmbreeDevice device;
    for (GeometryMode mode : {GeometryMode::Curves, GeometryMode::Tubes, GeometryMode::Grid}) {
        SCOPED_TRACE(modeName(mode));
        const std::unique_ptr<TraceGeometry> geometry = makeTraceGeometry(g, modeOptions(mode, cells, sides));
        const TraceScene scene(device, g, modeOptions(mode, cells, sides));
        EXPECT_EQ(scene.primitiveCount(), geometry->primitiveCount());
        EXPECT_EQ(scene.memory().geometryBytes, geometry->bytes());
        EXPECT_GT(geometry->bytes(), 0);
        const bool tubes = mode == GeometryMode::Tubes;
        EXPECT_EQ(geometry->sceneFlags(), tubes ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
        EXPECT_EQ(geometry->ignoredPrimitive(from), tubes ? 7u : RTC_INVALID_GEOMETRY_ID);
        EXPECT_EQ(geometry->inscribedRadius(), tubes ? std::cos(float(kPi) / sides) : 1.f);
    }
    EXPECT_EQ(makeCurveGeometry(g)->primitiveCount(), g.segmentCount());  // one curve per segment
    EXPECT_EQ(makeCurveGeometry(g)->bytes(), static_cast<int64_t>(g.intersectionBytes()));
    EXPECT_EQ(makeGridGeometry(g, &cells)->primitiveCount(), cellCount);  // one user primitive per cell
    // Tubes: sides * 2 triangles per ring gap, plus the two hemispheres of each open end.
    EXPECT_GT(makeTubeGeometry(g, sides)->primitiveCount(), 2u * sides * g.segmentCount());
}

TEST(PlyGeometry, closedLoopFiberPhaseHasNoSeam) {
    // A closed ply whose length is not a whole number of fiber turns: the fiber texture phase
    // tau_f v must still close (the loop is rescaled to whole turns), or the tables show a seam.
    const double tau = -1.5;  // PlyMaterial default fiber twist
    const int n = 97;
    const double radius = 20.3;  // ply radii: length 127.5, tau L / 2 pi = 30.45 turns
    std::vector<glm::dvec3> ring;
    for (int i = 0; i < n; ++i)
        ring.push_back(radius * glm::dvec3(std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0.0));
    const Plies plies = handMadePlies({ring}, true);
    double length = 0;
    for (int i = 0; i < n; ++i) length += glm::length(ring[(i + 1) % n] - ring[i]);
    auto seamTurns = [&](const PlyGeometry& g) {
        // The seam point p0 ends the last segment and starts the first one.
        const uint32_t first = g.segments[g.curveSegments[0]], last = g.segments[g.curveSegments[1] - 1] + 1;
        EXPECT_EQ(glm::vec3(g.points[first]), glm::vec3(g.points[last]));
        const double turns = std::abs(tau) * (double(g.arc[last]) - double(g.arc[first])) / (2 * kPi);
        return turns - std::round(turns);
    };
    const PlyGeometry plain = buildPlyGeometry(plies, glm::dvec3(0.0));
    EXPECT_GT(std::abs(seamTurns(plain)), 0.3);  // the case the rescale exists for
    const PlyGeometry g = buildPlyGeometry(plies, glm::dvec3(0.0), tau);
    EXPECT_NEAR(seamTurns(g), 0.0, 1e-4);
    // The rescale stays within half a turn over the loop.
    const double total = g.arc[g.segments[g.curveSegments[1] - 1] + 1] - g.arc[g.segments[g.curveSegments[0]]];
    EXPECT_LE(std::abs(total - length), kPi / std::abs(tau) + 1e-3);
    // End to end: the shading frame just before and just after the seam is the same.
    PlyMaterial m;
    m.fiberTwist = tau;
    const FiberTables tables = buildFiberTables(fiberTableOptions(m, 1));
    const uint32_t sFirst = g.curveSegments[0], sLast = g.curveSegments[1] - 1;
    for (const glm::dvec3 normal : {glm::dvec3(1, 0, 0), glm::dvec3(0.6, 0, 0.8), glm::dvec3(0, 0, -1)}) {
        PlySurfacePoint before, after;
        before.tangent = after.tangent = glm::dvec3(0, 1, 0);  // the ring's tangent at p0
        before.normal = after.normal = normal;
        before.radial = glm::dvec3(g.radial[g.segments[sLast] + 1]);
        after.radial = glm::dvec3(g.radial[g.segments[sFirst]]);
        before.v = g.arc[g.segments[sLast] + 1];
        after.v = g.arc[g.segments[sFirst]];
        const ShadingFrame a = plyShadingFrame(before, m, tables), b = plyShadingFrame(after, m, tables);
        EXPECT_GT(glm::dot(a.z, b.z), 1 - 1e-6);
        EXPECT_GT(glm::dot(a.x, b.x), 1 - 1e-6);
        EXPECT_NEAR(a.shadow, b.shadow, 1e-4);
    }
}

}  // namespace
}  // namespace knit
