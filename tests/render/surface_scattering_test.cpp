// The surface level's measured scattering (knit/surface_scattering.hpp): the table's sampling and
// interpolation, the table a bake measures, and the tracer shading with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include "knit/bake.hpp"
#include "knit/generator.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"
#include "knit/surface_scattering.hpp"
#include "test_util.hpp"
#include "tracing/trace_surface.hpp"

namespace knit {
namespace {

constexpr double kPi = 3.14159265358979323846;

SurfaceScattering randomTable(uint32_t seed) {
    SurfaceScattering s;
    s.side = 12;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const size_t n = size_t(s.bins());
    s.table.resize(3 * n * n);
    for (float& v : s.table) v = 0.02f * u(rng) * u(rng);
    s.pass.resize(n);
    for (float& v : s.pass) v = 0.3f * u(rng);
    s.prepare();
    return s;
}

glm::dvec3 uniformSphere(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double z = 1 - 2 * u(rng), phi = 2 * kPi * u(rng), r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// The sampling density integrates to one over the sphere, and sample() draws directions with it:
// the share of 200k samples per bin matches the density integrated over the bin.
TEST(SurfaceScattering, samplesFollowTheirDensity) {
    const SurfaceScattering s = randomTable(7);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const glm::dvec3 out : {glm::dvec3(0.1, 0.2, 0.97), glm::dvec3(0.9, -0.3, 0.1), glm::dvec3(-0.2, 0.5, -0.8)}) {
        const glm::dvec3 o = glm::normalize(out);
        double integral = 0;
        const int m = 200000;
        for (int k = 0; k < m; ++k) integral += s.pdf(o, uniformSphere(rng)) * 4 * kPi;
        EXPECT_NEAR(integral / m, 1.0, 0.01);
        std::vector<double> counts(size_t(s.bins()), 0.0), expected(size_t(s.bins()), 0.0);
        for (int k = 0; k < m; ++k) {
            const double r[4] = {u(rng), u(rng), u(rng), u(rng)};
            double pdf = 0;
            const glm::dvec3 in = s.sample(o, r, pdf);
            ASSERT_NEAR(glm::length(in), 1.0, 1e-9);
            ASSERT_NEAR(pdf, s.pdf(o, in), 1e-12);
            counts[size_t(s.binOf(in))] += 1;
        }
        // The density is constant over a bin: its integral there is pdf(bin centre) x solid angle.
        double chi2 = 0;
        for (int b = 0; b < s.bins(); ++b) {
            expected[size_t(b)] = m * s.pdf(o, s.binDirection(b, 0.5, 0.5)) * s.binSolidAngle();
            chi2 += (counts[size_t(b)] - expected[size_t(b)]) * (counts[size_t(b)] - expected[size_t(b)]) /
                    expected[size_t(b)];
        }
        EXPECT_LT(chi2, 380.0) << "chi-square over " << s.bins() << " bins";  // 287 dof: p ~ 2e-4
    }
}

// The bins: every direction drawn in a bin falls in it, the bins have equal solid angle (uniform
// directions fill them evenly), binCosine is the mean |cos| over the bin, and the normal is not a
// corner where the azimuth bins meet in a point (four bins of equal share touch it, as anywhere).
TEST(SurfaceScattering, binsHaveEqualSolidAngleAndHoldTheirDirections) {
    SurfaceScattering s;
    s.side = 12;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int b = 0; b < s.bins(); ++b)
        for (int k = 0; k < 20; ++k) {
            const glm::dvec3 w = s.binDirection(b, u(rng), u(rng));
            ASSERT_NEAR(glm::length(w), 1.0, 1e-6);
            ASSERT_EQ(s.binOf(w), b) << "bin " << b;
        }
    std::vector<double> count(size_t(s.bins()), 0.0), cosine(size_t(s.bins()), 0.0);
    const int m = 576000;
    for (int k = 0; k < m; ++k) {
        const glm::dvec3 w = uniformSphere(rng);
        count[size_t(s.binOf(w))] += 1;
        cosine[size_t(s.binOf(w))] += std::abs(w.z);
    }
    const double expected = double(m) / s.bins();  // 2000: sd 45
    for (int b = 0; b < s.bins(); ++b) {
        EXPECT_NEAR(count[size_t(b)], expected, 5 * std::sqrt(expected)) << "bin " << b;
        EXPECT_NEAR(cosine[size_t(b)] / count[size_t(b)], s.binCosine(b), 0.01) << "bin " << b;
    }
    EXPECT_NEAR(s.binSolidAngle() * s.bins(), 4 * kPi, 1e-12);
    int bins[4];
    double weights[4];
    s.interpolationCorners({0, 0, 1}, bins, weights);
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(weights[k], 0.25, 1e-12);
        EXPECT_GE(bins[k], s.bins() / 2) << "the normal's bins are on the front";
    }
}

// A table that is the same in every bin interpolates to that value everywhere, on both sides of
// the cloth; bins never straddle the cloth (z = 0 is on the front).
TEST(SurfaceScattering, uniformTableInterpolatesToItsValueOnBothSides) {
    SurfaceScattering s;
    s.side = 12;
    s.table.assign(size_t(3) * s.bins() * s.bins(), 0.01f);
    s.pass.assign(size_t(s.bins()), 0.25f);
    s.prepare();
    std::mt19937 rng(5);
    for (int k = 0; k < 1000; ++k) {
        const glm::dvec3 a = uniformSphere(rng), b = uniformSphere(rng);
        EXPECT_NEAR(s.eval(a, b).g, 0.01 / s.binSolidAngle(), 1e-7);  // float table
        EXPECT_NEAR(s.passAt(a), 0.25, 1e-7);
        EXPECT_NEAR(s.pdf(a, b), 1 / (4 * kPi), 1e-5);  // float cumulative sums
    }
    EXPECT_GE(s.binOf({1, 0, 0}), s.bins() / 2) << "z = 0 is on the front";
    EXPECT_LT(s.binOf({1, 0, -1e-12}), s.bins() / 2);
    EXPECT_GE(s.binOf({0, 0, 1}), s.bins() / 2);
    EXPECT_LT(s.binOf({0, 0, -1}), s.bins() / 2);
}

BakeOptions scatteringBake(int paths) {
    BakeOptions o;
    o.width = 32;
    o.samplesPerAxis = 4;
    o.albedoPaths = 4;
    o.plies.count = 2;
    o.scatteringPaths = paths;
    return o;
}

double frontSum(const SurfaceScattering& s, int row, int channel) {
    double sum = 0;
    for (int b = s.bins() / 2; b < s.bins(); ++b) sum += s.table[3 * (size_t(row) * s.bins() + b) + channel];
    return sum;
}

// Seen from above, the table agrees with the textures baked straight down: the holes (pass) are
// at most the uncovered share, the light sent back up is the mean albedo times the coverage.
// Seen at a grazing angle the yarns hide the holes (an endless cloth: PeriodicCloth; rays that
// left the generated tiles sideways made the grazing pass 0.40 against 0.15 from above). No row
// sends more than it gets.
TEST(SurfaceScattering, bakedTableAgreesWithTheTexturesAndClosesItsHolesAtGrazingAngles) {
    const SurfaceBake b = bakeSurface(generateStockinette(), scatteringBake(4096));
    const SurfaceScattering& s = b.scattering;
    ASSERT_FALSE(s.empty());
    // The bins around +z: the middle 4 x 4 of the front's square (within ~28 degrees of the normal).
    std::vector<int> top;
    for (int y = s.side / 2 - 2; y < s.side / 2 + 2; ++y)
        for (int x = s.side / 2 - 2; x < s.side / 2 + 2; ++x) top.push_back(s.side * s.side + y * s.side + x);
    double pass = 0, reflected = 0;
    for (int row : top) pass += s.pass[size_t(row)] / double(top.size());
    for (int row : top) reflected += frontSum(s, row, 0) / double(top.size());
    double albedo = 0;
    for (size_t i = 0; i < b.coverage.size(); ++i) albedo += b.coverage[i] * b.albedo[3 * i];
    albedo /= double(b.coverage.size());
    std::printf("top: pass %.4f (1 - coverage %.4f), red sent up %.4f (albedo x coverage %.4f)\n", pass,
                1 - b.meanCoverage(), reflected, albedo);
    // The top bins reach 28 degrees off the normal, where the yarns already hide some of the holes
    // seen straight down.
    EXPECT_LT(pass, 1 - b.meanCoverage() + 0.01);
    EXPECT_GT(pass, 0.7 * (1 - b.meanCoverage()));
    EXPECT_NEAR(reflected / albedo, 1.0, 0.08);
    // The front's outer ring of bins (the square's edge: z in [0, 0.31], 72 to 90 degrees).
    std::vector<int> grazing;
    for (int b = s.bins() / 2; b < s.bins(); ++b) {
        const int x = b % s.side, y = (b / s.side) % s.side;
        if (x == 0 || y == 0 || x == s.side - 1 || y == s.side - 1) grazing.push_back(b);
    }
    double grazingPass = 0;
    for (int row : grazing) grazingPass += s.pass[size_t(row)] / double(grazing.size());
    EXPECT_LT(grazingPass, 0.5 * pass) << "grazing pass " << grazingPass;
    // Reciprocity: f(in, out) = table(out, in) / |cos in| is symmetric.
    auto cosine = [&](int bin) { return s.binCosine(bin); };
    for (int o = 0; o < s.bins(); o += 7)
        for (int i = 0; i < s.bins(); i += 5)
            EXPECT_NEAR(s.table[3 * (size_t(o) * s.bins() + i)] / cosine(i),
                        s.table[3 * (size_t(i) * s.bins() + o)] / cosine(o), 1e-5);
    for (int row = 0; row < s.bins(); ++row)
        for (int c = 0; c < 3; ++c) {
            double sum = s.pass[size_t(row)];
            for (int in = 0; in < s.bins(); ++in) sum += s.table[3 * (size_t(row) * s.bins() + in) + c];
            EXPECT_LE(sum, 1.02) << "row " << row << " channel " << c;
        }
}

// Focus: the same number of paths, most of them spent on the rows of the directions a view needs
// (its camera and its light), estimate the entries between those directions with less noise
// than paths spread evenly: over six seeds, the spread of f(camera, light) is at least halved.
TEST(SurfaceScattering, focusedPathsMeasureTheViewsDirectionsWithLessNoise) {
    const glm::dvec3 eye = glm::normalize(glm::dvec3(0.1, 0.05, 1)), light = glm::normalize(glm::dvec3(0.4, 0.4, 1));
    auto spread = [&](bool focused, size_t& paths) {
        double sum = 0, sum2 = 0;
        const int seeds = 6;
        for (int seed = 1; seed <= seeds; ++seed) {
            BakeOptions o = scatteringBake(256);
            o.width = 8, o.albedoPaths = 0;
            o.seed = uint64_t(seed);
            if (focused) o.scatteringFocus = {{eye, 1.0}, {light, 1.0}};
            const SurfaceBake b = bakeSurface(generateStockinette(), o);
            const double f = b.scattering.eval(eye, light).g;
            sum += f, sum2 += f * f;
            paths = b.scattering.paths;
        }
        const double mean = sum / seeds;
        return std::sqrt(std::max(0.0, sum2 / seeds - mean * mean)) / mean;
    };
    size_t evenPaths = 0, focusedPaths = 0;
    const double even = spread(false, evenPaths), focused = spread(true, focusedPaths);
    std::printf("relative spread of f(eye, light): even %.4f, focused %.4f (%zu / %zu paths)\n", even, focused,
                evenPaths, focusedPaths);
    EXPECT_LT(focused, 0.5 * even);
    EXPECT_NEAR(double(focusedPaths), double(evenPaths), 0.01 * double(evenPaths)) << "the same budget";
}

TEST(SurfaceScattering, bakedTableIsTheSameForAnyThreadCount) {
    const SurfaceBake a = bakeSurface(generateStockinette(), scatteringBake(256));
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const SurfaceBake b = bakeSurface(generateStockinette(), scatteringBake(256));
    EXPECT_EQ(a.scattering.table, b.scattering.table);
    EXPECT_EQ(a.scattering.pass, b.scattering.pass);
    EXPECT_EQ(a.albedo, b.albedo) << "the table does not change the textures' paths";
}

TEST(SurfaceScattering, badPathCountNamesTheOption) {
    BakeOptions o = scatteringBake(-1);
    EXPECT_NE(test::errorOf([&] { bakeSurface(generateStockinette(), o); }).find("the scattering paths"),
              std::string::npos);
    o = scatteringBake(16);
    o.scatteringSide = 0;
    EXPECT_NE(test::errorOf([&] { bakeSurface(generateStockinette(), o); }).find("scatteringSide"), std::string::npos);
    o = scatteringBake(16);
    o.scatteringFocusShare = 1.5;
    EXPECT_NE(test::errorOf([&] { bakeSurface(generateStockinette(), o); }).find("scatteringFocusShare"),
              std::string::npos);
}

// A plane (+y up, u along +x, v along -z) without plies, `yarnRadius` metres to the scene unit.
Scene planeScene(double yarnRadius) {
    SceneParts parts;
    parts.mesh = makePlane();
    parts.normals = vertexNormals(parts.mesh.positions, parts.mesh.faces);
    parts.yarnRadius = yarnRadius;
    return Scene::fromParts(std::move(parts));
}

// A 1 x 1 bake, fully covered, of albedo `a`, with the table `s`.
SurfaceBake tableBake(const SurfaceScattering& s, double a) {
    SurfaceBake b;
    b.width = b.height = 1;
    b.albedo = {float(a), float(a), float(a)};
    b.coverage = {1.f};
    b.normal = {0.f, 0.f, 1.f};
    b.heights = {0.f};
    b.scattering = s;
    return b;
}

double planeMiddle(const Image& im) {
    double g = 0;
    for (int y = 9; y <= 14; ++y)
        for (int x = 9; x <= 14; ++x) g += im.pixel(x, y).g;
    return g / 36;
}

RenderOptions furnace(const SurfaceBake& bake) {
    RenderOptions o;
    o.width = o.height = 24;
    o.spp = 256;
    o.progress = false;
    o.surface = &bake;
    o.surfaceRepeats[0] = o.surfaceRepeats[1] = 1;
    o.material.tableSize = 64, o.material.aoRays = 16;
    o.environment = 1, o.lightIrradiance = 0;
    return o;
}

// White furnace for the table in the tracer: under a uniform environment alone, a surface that
// lets a share p through its holes and scatters the rest (a table whose rows sum to 1 - p) sends
// the environment's radiance back, whatever p: the stochastic holes, the hit's weight 1 / (1 - p),
// the table's sampling and MIS add up. A table scattering half of it sends (1 + p) / 2.
TEST(SurfaceScattering, furnaceSendsBackWhatTheTableScattersPlusWhatPassesThrough) {
    const Scene scene = planeScene(0.001);
    for (const double p : {0.0, 0.3, 0.7})
        for (const double keep : {1.0, 0.5}) {
            SurfaceScattering s;
            s.side = 12;
            s.table.assign(size_t(3) * s.bins() * s.bins(), float(keep * (1 - p) / s.bins()));
            s.pass.assign(size_t(s.bins()), float(p));
            s.prepare();
            const SurfaceBake bake = tableBake(s, 0.5);
            const double v = planeMiddle(renderScene(scene, furnace(bake)).image);
            std::printf("furnace: pass %.1f, scattered %.1f: %.5f\n", p, keep, v);
            EXPECT_NEAR(v, p + keep * (1 - p), 0.012);
        }
}

// The prefiltered texture camera rays read (SurfaceTexture::levels): on an odd-sized bake every
// level averages exactly the texels it covers, so the top level is the cell's mean: the holes
// relative to their mean are 1 there, and the tint (weighted by the coverage, where hits land) too.
TEST(SurfaceScattering, prefilteredTextureKeepsTheCellsMeansOnOddSizes) {
    SurfaceBake bake;
    bake.width = 5, bake.height = 3;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.05f, 1.f);
    for (int i = 0; i < 15; ++i) {
        bake.coverage.push_back(u(rng));
        for (int c = 0; c < 3; ++c) bake.albedo.push_back(0.5f * u(rng));
    }
    bake.normal.assign(45, 0.f), bake.heights.assign(15, 0.f);
    bake.scattering = randomTable(3);
    const SurfaceTexture t = makeSurfaceTexture(bake, {1.0, 1.0});
    ASSERT_EQ(t.levels.size(), 4u);  // 5 x 3, 3 x 2, 2 x 1, 1 x 1
    const SurfaceTexture::Level& top = t.levels.back();
    ASSERT_EQ(top.width * top.height, 1);
    EXPECT_NEAR(top.holes[0], 1.0, 1e-5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(top.tint[c], 1.0, 1e-5);
    // Level 1's last column covers level 0's column 4 alone (clipped, not wrapped).
    const SurfaceTexture::Level& one = t.levels[1];
    EXPECT_NEAR(one.holes[2], 0.5 * (t.levels[0].holes[4] + t.levels[0].holes[9]), 1e-6);
}

// Far from the scene's origin in scene units (a garment is thousands of yarn radii across), rays
// leaving the surface must not hit their own triangle again: the furnace is as bright with a
// yarn radius of a micrometre as with a millimetre (it was 8% darker on the garment of issue 11).
TEST(SurfaceScattering, surfaceFarFromTheOriginDoesNotShadowItself) {
    SurfaceBake bake;
    bake.width = bake.height = 1;
    bake.albedo = {0.6f, 0.6f, 0.6f};
    bake.coverage = {1.f};
    bake.normal = {0.f, 0.f, 1.f};
    bake.heights = {0.f};
    const double near = planeMiddle(renderScene(planeScene(1e-3), furnace(bake)).image);
    const double far = planeMiddle(renderScene(planeScene(1e-7), furnace(bake)).image);
    std::printf("furnace, albedo 0.6: yarn radius 1 mm %.5f, 0.1 um %.5f\n", near, far);
    EXPECT_NEAR(near, 0.6, 0.006);
    EXPECT_NEAR(far, 0.6, 0.006);
}

}  // namespace
}  // namespace knit
