// Tracer tests: self-intersection, furnace, the three geometry modes agree, back-lit transmission,
// determinism, image files and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <glm/geometric.hpp>
#include <stb/stb_image.h>
#include <tbb/global_control.h>
#include <tinyexr.h>

#include "image_match.hpp"
#include "knit/error.hpp"
#include "knit/image_io.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/render.hpp"
#include "knit/synthetic_scene.hpp"
#include "tracing/trace_scene.hpp"
#include "common/test_paths.hpp"

namespace knit {
namespace {

const GeometryMode kModes[] = {GeometryMode::Curves, GeometryMode::Tubes, GeometryMode::Grid};

SyntheticSceneOptions wavyCloth() {
    SyntheticSceneOptions o;
    o.courses = 5;
    o.size = 0.01;
    o.yarnRadius = 0.0008;
    o.plyCount = 3;
    o.waveAmplitude = 0.0004;
    o.waveLength = 0.006;
    o.cellSize = 0.25;
    return o;
}

std::string tmpFile(const std::string& name) { return std::string(test::binaryDir()) + "/render_test_" + name; }

struct Built {
    Scene scene;
    PlyGeometry geometry;
    std::vector<int64_t> cells;
};

Built build(const SyntheticSceneOptions& o) {
    Built b;
    b.scene = makeSyntheticPlyScene(o);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : b.scene.plies().curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    b.geometry = buildPlyGeometry(b.scene.plies(), 0.5 * (lo + hi));
    b.cells = segmentCells(b.scene, b.geometry);
    return b;
}

TraceSceneOptions modeOptions(GeometryMode m, const Built& b, int sides = 8) {
    TraceSceneOptions so;
    so.mode = m;
    so.tubeSides = sides;
    so.segmentCells = &b.cells;
    return so;
}

glm::vec3 randomHemisphere(std::mt19937& rng, const glm::vec3& n) {
    std::normal_distribution<float> g;
    glm::vec3 v(g(rng), g(rng), g(rng));
    v = glm::normalize(v);
    return glm::dot(v, n) < 0 ? -v : v;
}

// Fires rays at the cloth; from every ply hit, spawns reflected and transmitted rays and counts
// those whose next hit is on the very segment they leave.
int countSelfHits(const TraceScene& ts, int rays, int* spawned) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> uni(-0.005f, 0.005f);
    int self = 0;
    *spawned = 0;
    for (int i = 0; i < rays; ++i) {
        const glm::dvec3 c = ts.plies().origin;  // the cloth centre
        const glm::dvec3 orgW = c + glm::dvec3(uni(rng), uni(rng), i % 2 ? 0.02 : -0.02);
        const glm::dvec3 targetW = c + glm::dvec3(uni(rng), uni(rng), 0.0);
        const glm::vec3 org = ts.plies().toScene(orgW), dir = glm::normalize(ts.plies().toScene(targetW) - org);
        TraceHit h;
        if (!ts.intersect(org, dir, 0.f, 1e30f, h) || h.kind != TraceHit::Ply) continue;
        const glm::vec3 p = org + h.t * dir;
        for (int k = 0; k < 4; ++k) {
            const glm::vec3 w = randomHemisphere(rng, k % 2 ? h.ng : -h.ng);
            TraceHit next;
            ++*spawned;
            // The origin primitive: the triangle (tubes) or the ply segment (curves, grid cells).
            if (ts.intersect(ts.spawn(h, p, w), w, 0.f, 1e30f, next, &h) && next.kind == TraceHit::Ply &&
                (ts.mode() == GeometryMode::Tubes ? next.primID == h.primID : next.segment == h.segment))
                ++self;
        }
    }
    return self;
}

TEST(TraceScene, spawnedRayNeverReHitsItsOriginPrimitive) {
    const Built b = build(wavyCloth());
    EmbreeDevice device;
    for (GeometryMode m : kModes) {
        const TraceScene ts(device, b.geometry, modeOptions(m, b));
        int spawned = 0;
        EXPECT_EQ(countSelfHits(ts, 3000, &spawned), 0) << modeName(m);
        EXPECT_GT(spawned, 4000) << modeName(m);
    }
}

TEST(TraceScene, withoutOffsetsTransmittedRaysReHitTheirOrigin) {
    // The offsets are what prevents self-hits: with both set to zero, rays leaving into the ply
    // from a point computed slightly outside re-enter the same segment.
    const Built b = build(wavyCloth());
    EmbreeDevice device;
    int total = 0;
    for (GeometryMode m : {GeometryMode::Curves, GeometryMode::Grid}) {  // tubes also filter
        TraceScene ts(device, b.geometry, modeOptions(m, b));
        ts.insideOffset = -0.03f;  // start just outside the surface: the case an offset must fix
        int spawned = 0;
        total += countSelfHits(ts, 1000, &spawned);
    }
    EXPECT_GT(total, 100);
}

TEST(TraceScene, gridModeHitsLieOnThePlySurfaceAndMatchCurves) {
    // Same rays, same segments: the two-stage cells find the same plies as Embree's round linear
    // curves, and their hits lie on the swept surface (distance to the own centreline = radius,
    // up to the mitre at joints).
    const Built b = build(wavyCloth());
    EmbreeDevice device;
    const TraceScene curves(device, b.geometry, modeOptions(GeometryMode::Curves, b));
    const TraceScene grid(device, b.geometry, modeOptions(GeometryMode::Grid, b));
    const PlyGeometry& g = b.geometry;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(-0.004f, 0.004f);
    int both = 0, close = 0, onlyOne = 0, onSurface = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 org = g.toScene(g.origin + glm::dvec3(uni(rng), uni(rng), 0.02));
        const glm::vec3 dir = glm::normalize(glm::vec3(uni(rng), uni(rng), -0.02f));
        TraceHit a, c;
        const bool ha = curves.intersect(org, dir, 0.f, 1e30f, a), hc = grid.intersect(org, dir, 0.f, 1e30f, c);
        if (ha != hc) ++onlyOne;
        if (!hc) continue;
        const uint32_t j = g.segments[c.segment];
        const glm::vec3 p0(g.points[j]), p1(g.points[j + 1]), p = org + c.t * dir;
        const float t = glm::clamp(glm::dot(p - p0, p1 - p0) / glm::dot(p1 - p0, p1 - p0), 0.f, 1.f);
        const float dist = glm::length(p0 + t * (p1 - p0) - p) / g.radius;
        onSurface += dist > 0.999f && dist < 1.01f;
        if (ha) {
            ++both;
            close += std::abs(a.t - c.t) < 0.02f * g.radius;
        }
    }
    EXPECT_GT(both, 5000);
    EXPECT_GT(onSurface, 0.99 * both);
    EXPECT_GT(close, 0.99 * both);
    EXPECT_LT(onlyOne, 0.01 * both);
    EXPECT_LT(grid.primitiveCount(), b.geometry.segmentCount() / 20);
}

RenderOptions smallRender() {
    RenderOptions o;
    o.width = 40;
    o.height = 30;
    o.spp = 16;
    o.progress = false;
    return o;
}

TEST(Render, furnaceSceneRendersRadianceOne) {
    // Lossless plies (all energy scattered, no shadowing) under a white environment: every pixel
    // sees radiance 1 whatever the geometry.
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.environment = 1.0;
    o.lightIrradiance = 0.0;
    o.maxDepth = 200;
    o.material.kR = Rgb(0.0);
    o.material.kTT = Rgb(0.0);
    o.material.bodyAlbedo = Rgb(1.0);
    o.material.fiberDetail = false;
    o.material.fiberShadowFloor = 1.0;
    o.material.plyShadowFloor = 1.0;
    for (const char* mode : {"curves", "grid", "tubes"}) {
        o.mode = parseMode(mode);
        const RenderResult r = renderScene(scene, o);
        double sum = 0, var = 0;
        for (size_t i = 0; i < r.image.variance.size(); ++i) {
            sum += r.image.rgb[3 * i];
            var += r.image.variance[i];
        }
        const double n = double(r.image.variance.size());
        const double mean = sum / n, se = std::sqrt(var) / n;
        EXPECT_NEAR(mean, 1.0, 4 * se + 2e-3) << mode;
    }
}

TEST(Render, threeModesRenderMatchingImages) {
    // Independent seeds per mode; the statistical criterion of image_match.hpp at alpha 1e-4
    // per statistic (4 statistics here).
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.spp = 64;
    o.tubeSides = 32;
    std::vector<Image> images;
    uint64_t seed = 1;
    for (const char* mode : {"curves", "grid", "tubes"}) {
        o.mode = parseMode(mode);
        o.seed = seed++;
        images.push_back(renderScene(scene, o).image);
    }
    for (int k = 1; k < 3; ++k) {
        const ImageMatch m = matchImages(images[0], images[k], 5);
        EXPECT_TRUE(m.within(1e-4)) << "mode " << k << ": " << m;
        EXPECT_LT(m.comparison.meanAbsDifference, 0.1 * luminance(images[0].mean())) << "mode " << k;
    }
    // And the comparison can tell different images apart: front vs back light (the background
    // blocks, lit by the environment only, are equal in both).
    o.mode = GeometryMode::Curves;
    o.light = LightPlacement::Back;
    const Image back = renderScene(scene, o).image;
    const ImageComparison diff = compareImages(images[0], back, 5, 4.0);
    EXPECT_GT(diff.outliers, diff.blocks / 3);
    EXPECT_FALSE(matchImages(images[0], back, 5).within(1e-4));
}

TEST(Render, backLitImageShowsTransmittedLight) {
    SyntheticSceneOptions dense = wavyCloth();
    dense.courses = 8;  // overlapping single-ply yarns: no gap to see the light through
    dense.yarnRadius = 0.01 / 14;
    dense.plyCount = 1;
    const Scene scene = makeSyntheticPlyScene(dense);
    RenderOptions o = smallRender();
    o.light = LightPlacement::Back;
    o.environment = 0.0;
    o.material.kTT = Rgb(0.3);
    o.material.kR = Rgb(0.3);
    o.material.bodyAlbedo = Rgb(0.6);
    o.material.reflectFraction = 0.3;
    const RenderResult lit = renderScene(scene, o);
    // Pixels in the central window all look at cloth (the camera frames the cloth's bounds).
    auto centre = [&](const Image& im, int& bright) {
        double sum = 0;
        int pixels = 0;
        bright = 0;
        // The middle 40% in x (the default camera frames the base mesh grown by the yarns' margin,
        // so the light is seen past the cloth's left and right edges beyond 0.3 and 0.7).
        for (int y = o.height / 4; y < 3 * o.height / 4; ++y)
            for (int x = 3 * o.width / 10; x < 7 * o.width / 10; ++x, ++pixels) {
                bright += im.pixel(x, y).y > 0;
                sum += luminance(im.pixel(x, y));
            }
        return sum / pixels;
    };
    int bright = 0;
    const double litMean = centre(lit.image, bright);
    EXPECT_GT(bright, 0.95 * (7 * o.width / 10 - 3 * o.width / 10) * (o.height / 2));
    // Without transmission lobes the back-lit cloth is much darker.
    o.material.kTT = Rgb(0.0);
    o.material.reflectFraction = 1.0;
    const RenderResult opaque = renderScene(scene, o);
    int unused = 0;
    EXPECT_GT(litMean, 5 * centre(opaque.image, unused));
}

TEST(Render, frontLightNeverHidesTheViewInANarrowField) {
    // With a 2-degree view the camera is ~57 scene radii away and the front light (2.5 radii in
    // front of the cloth) lies inside the view; seen from behind it must not be there (it was a
    // black square over the image).
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.fovDegrees = 2;
    o.spp = 4;
    const Image image = renderScene(scene, o).image;
    int black = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) black += luminance(image.pixel(x, y)) <= 0;
    // Every pixel sees the environment (0.05) or lit cloth, unless all 4 of its paths stay in
    // shadowed cloth (the environment is found only by scattered rays): a few scattered pixels,
    // never the light's square over the image.
    EXPECT_LE(black, image.width * image.height / 100) << black << " black pixels";
}

TEST(Render, pixelStrataMakeTwoSeedsCloserThanIndependentSamplesWould) {
    // A pixel's samples cover it by strata (render_image.hpp), so two seeds differ by less than
    // the variance of independent samples (Image::variance, from the samples' spread) predicts:
    // the expected ratio is 1 for independent points in the pixel. Black plies before a white
    // environment: a pixel's value is the part of it the plies leave open, all of its noise is
    // where the samples fall in it.
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.environment = 1, o.lightIrradiance = 0;
    o.material.bodyAlbedo = o.material.kR = o.material.kTT = Rgb(0.0);
    const Image a = renderScene(scene, o).image;
    o.seed = 2;
    const Image b = renderScene(scene, o).image;
    double diff = 0, predicted = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const double d = luminance(a.pixel(x, y)) - luminance(b.pixel(x, y));
            diff += d * d;
            predicted += a.variance[size_t(y) * a.width + x] + b.variance[size_t(y) * a.width + x];
        }
    std::printf("squared difference of two seeds / independent samples' variance: %.3f\n", diff / predicted);
    EXPECT_LT(diff, 0.6 * predicted);  // 0.24 measured; 0.99 with independent points
}

TEST(Render, deterministicForSeedAndThreadCount) {
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.mode = GeometryMode::Grid;
    const Image a = renderScene(scene, o).image;
    Image b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        b = renderScene(scene, o).image;
    }
    EXPECT_EQ(a.rgb, b.rgb);
    o.seed = 2;
    EXPECT_NE(a.rgb, renderScene(scene, o).image.rgb);
}

TEST(Render, farFromOriginRendersLikeAtOrigin) {
    SyntheticSceneOptions far = wavyCloth();
    far.offset = glm::dvec3(1e5, -2e5, 3e4);  // 100 km away: float32 world coordinates would fail
    RenderOptions o = smallRender();
    o.mode = GeometryMode::Grid;
    const Image a = renderScene(makeSyntheticPlyScene(wavyCloth()), o).image;
    const Image b = renderScene(makeSyntheticPlyScene(far), o).image;
    const ImageComparison c = compareImages(a, b, 5, 4.0);
    EXPECT_LE(c.outliers, c.blocks / 12);
}

TEST(Render, pngAndExrAreWrittenAndReadBack) {
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.output = tmpFile("image.png");
    o.exr = tmpFile("image.exr");
    const RenderResult r = renderScene(scene, o);
    int w, h, n;
    unsigned char* px = stbi_load(o.output.c_str(), &w, &h, &n, 3);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(w, 40);
    EXPECT_EQ(h, 30);
    stbi_image_free(px);
    float* rgba = nullptr;
    const char* err = nullptr;
    ASSERT_EQ(LoadEXR(&rgba, &w, &h, o.exr.c_str(), &err), TINYEXR_SUCCESS);
    EXPECT_FLOAT_EQ(rgba[4 * 17 + 1], r.image.rgb[3 * 17 + 1]);  // linear values kept exactly
    free(rgba);
    EXPECT_GT(r.raysPerSecond, 0);
    EXPECT_GT(r.memory.sceneBytes(), 0);
    EXPECT_GT(r.peakMemoryBytes, 0);
    EXPECT_EQ(r.written, (std::vector<std::string>{o.output, o.exr}));
    std::remove(o.output.c_str());
    std::remove(o.exr.c_str());
}

void expectError(const Scene& scene, const RenderOptions& o, const std::string& fragment) {
    try {
        renderScene(scene, o);
        FAIL() << "no error, expected one mentioning " << fragment;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

TEST(Render, badInputIsAClearError) {
    const Scene scene = makeSyntheticPlyScene(wavyCloth());
    RenderOptions o = smallRender();
    o.spp = 0;
    expectError(scene, o, "samples per pixel");
    o = smallRender();
    o.materialOverrides["kR"] = {0.8};
    o.materialOverrides["bodyAlbedo"] = {0.5};
    expectError(scene, o, "energy");
    o = smallRender();
    o.materialOverrides["alphaAlong"] = {5.0};
    expectError(scene, o, "alphaAlong");
    o = smallRender();
    o.mode = static_cast<GeometryMode>(7);
    expectError(scene, o, "unknown geometry mode 7");
    o = smallRender();
    expectError(Scene(), o, "no ply curves");
    o.output = "/nonexistent-folder/knit/image.png";
    expectError(scene, o, "/nonexistent-folder/knit/image.png");
    EXPECT_FALSE(std::filesystem::exists(o.output));
}

// An image whose write fails (its path is a folder) leaves nothing beside it: no temporary file
// of any name (the writer stages `.<name>.<pid>.<n>.tmp` and renames it when complete).
TEST(Render, failedWriteLeavesNoPartialFile) {
    const std::filesystem::path folder = tmpFile("failed_write");
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder / "out.png");  // a folder where the image should go
    Image im;
    im.width = 2, im.height = 2;
    im.rgb.assign(12, 0.5f);
    EXPECT_THROW(checkWritable((folder / "out.png").string()), Error);
    EXPECT_THROW(writePng((folder / "out.png").string(), im), Error);
    EXPECT_THROW(writeExr((folder / "out.png").string(), im), Error);
    std::vector<std::string> left;
    for (const auto& e : std::filesystem::directory_iterator(folder)) left.push_back(e.path().filename().string());
    EXPECT_EQ(left, std::vector<std::string>{"out.png"});
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace knit
