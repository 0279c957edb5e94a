// Surface bake tests: the textures tile, coverage is the projected area of the plies, the plies
// repeat with the period, bad options are named.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include "bake/bake_plies.hpp"
#include "knit/bake.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

BakeOptions smallBake() {
    BakeOptions o;
    o.width = 32;
    o.samplesPerAxis = 2;
    o.albedoPaths = 2;
    o.plies.count = 2;
    return o;
}

// Mean absolute difference of one channel between image columns a and b.
double columnDifference(const std::vector<float>& map, int channels, int channel, int w, int h, int a, int b) {
    double sum = 0;
    for (int k = 0; k < h; ++k)
        sum += std::abs(map[(size_t(k) * w + a) * channels + channel] - map[(size_t(k) * w + b) * channels + channel]);
    return sum / h;
}

// Mean absolute difference between map b and map a rolled by `shift` columns (b(c) ~ a(c + shift)).
double rolledDifference(const std::vector<float>& a, const std::vector<float>& b, int channels, int w, int h,
                        int shift) {
    double sum = 0;
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
            for (int k = 0; k < channels; ++k)
                sum += std::abs(b[(size_t(r) * w + c) * channels + k] -
                                a[(size_t(r) * w + (c + shift) % w) * channels + k]);
    return sum / (double(w) * h * channels);
}

struct SeamCheck {
    double rolled = 0;  // shifted bake against the rolled bake, mean over pixels
    double edge = 0;    // normal x across the bake's left/right edge
    double same = 0;    // the same pixel pair inside the shifted bake (no seam there)
};

// A bake from origin (0, 0) and one from origin (0.5, 0): the second sees the first's left/right
// edge in its middle, as interior neighbours. Tileable textures: the second is the first rolled
// by half a width, and the edge difference equals the interior one at the same place.
SeamCheck seamCheck(const Pattern& p, BakeOptions o) {
    o.albedoPaths = 0;  // deterministic maps only (albedo paths are noise)
    const SurfaceBake a = bakeSurface(p, o);
    o.origin[0] = 0.5;
    const SurfaceBake b = bakeSurface(p, o);
    const int w = a.width, h = a.height, half = w / 2;
    SeamCheck s;
    s.rolled =
        (rolledDifference(a.coverage, b.coverage, 1, w, h, half) +
         rolledDifference(a.heights, b.heights, 1, w, h, half) + rolledDifference(a.normal, b.normal, 3, w, h, half)) /
        3;
    s.edge = columnDifference(a.normal, 3, 0, w, h, w - 1, 0);
    s.same = columnDifference(b.normal, 3, 0, w, h, half - 1, half);
    return s;
}

TEST(Bake, bakedTexturesTileSeamlessly) {
    const SeamCheck s = seamCheck(generateStockinette(), smallBake());
    EXPECT_LT(s.rolled, 1e-3);  // measured 3e-8: only float rounding differs
    EXPECT_NEAR(s.edge, s.same, 1e-3);
}

TEST(Bake, bakedTexturesTileSeamlesslyAlongY) {
    BakeOptions o = smallBake();
    o.albedoPaths = 0;
    const Pattern p = generateStockinette();
    const SurfaceBake a = bakeSurface(p, o);
    const int shift = a.height / 2;  // whole rows (M may be odd): origin shift / M periods
    o.origin[1] = double(shift) / a.height;
    const SurfaceBake b = bakeSurface(p, o);
    // Rows count down from the top: moving the origin up by `shift` rows, b's row r + shift is a's row r.
    double sum = 0;
    for (int r = 0; r < a.height; ++r)
        for (int c = 0; c < a.width; ++c) {
            const size_t pa = size_t(r) * a.width + c, pb = size_t((r + shift) % a.height) * a.width + c;
            sum += std::abs(a.coverage[pa] - b.coverage[pb]) + std::abs(a.heights[pa] - b.heights[pb]);
        }
    EXPECT_LT(sum / (2.0 * a.width * a.height), 1e-3);
}

// Without the pitch adjustment the ply phase jumps at the period: the same check fails there
// (the tests above can fail).
TEST(Bake, unadjustedPlyPitchLeavesASeam) {
    BakeOptions o = smallBake();
    o.periodicPitch = false;
    o.plies.pitch = 0.37 * generateStockinette().px;  // not a divisor of the yarn's period length
    const SeamCheck s = seamCheck(generateStockinette(), o);
    EXPECT_GT(s.rolled, 0.03);  // measured 0.073
}

TEST(Bake, periodicPitchRepeatsThePliesOverOnePeriod) {
    const Pattern p = generateStockinette();
    PlyOptions po;
    po.count = 3;
    const BakePlies bp = bakePlies(p, po, true);
    ASSERT_FALSE(bp.yarnPitch.empty());
    // Every ply point of a yarn has a partner one period further along x on the same ply curve
    // (the courses run along x), when that translate lies inside the generated tiles.
    int checked = 0;
    for (size_t c = 0; c < bp.plies.curves.curveCount(); ++c) {
        const uint32_t b = bp.plies.curves.begin(c), e = bp.plies.curves.end(c);
        for (uint32_t i = b; i < e; i += 7) {
            const glm::dvec3 target = bp.plies.curves.points[i] + glm::dvec3(p.px, 0, 0);
            double best = 1e9;
            for (uint32_t j = b; j + 1 < e; ++j) {
                const glm::dvec3 a = bp.plies.curves.points[j], d = bp.plies.curves.points[j + 1] - a;
                const double t = std::clamp(glm::dot(target - a, d) / glm::dot(d, d), 0.0, 1.0);
                best = std::min(best, glm::length(a + t * d - target));
            }
            if (target.x > 0.5 * p.px && target.x < 1.5 * p.px) {
                EXPECT_LT(best, 0.05 * bp.yarnRadius) << "curve " << c << " point " << i - b;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 10);
}

// Fraction of a fine grid over the cell inside the union of the ply segments' projections
// (a round ply segment projects to the 2D capsule of its projected segment).
double projectedPlyCoverage(const BakePlies& bp, double px, double py, int n) {
    struct Seg {
        glm::dvec2 a, b;
    };
    std::vector<Seg> segs;
    const Polylines& c = bp.plies.curves;
    const double r = bp.plies.plyRadius;
    for (size_t k = 0; k < c.curveCount(); ++k)
        for (uint32_t i = c.begin(k); i < c.end(k); ++i) {
            const uint32_t j = i + 1 < c.end(k) ? i + 1 : (c.isClosed(k) ? c.begin(k) : i);
            const glm::dvec2 a(c.points[i]), b(c.points[j]);
            if (std::max(a.x, b.x) > -r && std::min(a.x, b.x) < px + r && std::max(a.y, b.y) > -r &&
                std::min(a.y, b.y) < py + r)
                segs.push_back({a, b});
        }
    int inside = 0;
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix) {
            const glm::dvec2 q((ix + 0.5) / n * px, (iy + 0.5) / n * py);
            for (const Seg& s : segs) {
                const glm::dvec2 d = s.b - s.a;
                const double dd = glm::dot(d, d);
                const double t = dd > 0 ? std::clamp(glm::dot(q - s.a, d) / dd, 0.0, 1.0) : 0.0;
                if (glm::length(s.a + t * d - q) <= r) {
                    ++inside;
                    break;
                }
            }
        }
    return double(inside) / (double(n) * n);
}

TEST(Bake, coverageIsTheProjectedAreaOfThePlies) {
    const Pattern p = generateStockinette();
    BakeOptions o = smallBake();
    o.albedoPaths = 0;
    o.samplesPerAxis = 4;
    const SurfaceBake b = bakeSurface(p, o);
    const double baked = b.meanCoverage();
    EXPECT_GT(baked, 0.05);
    EXPECT_LT(baked, 0.999);
    const double brute = projectedPlyCoverage(bakePlies(p, o.plies, true), p.px, p.py, 160);
    EXPECT_NEAR(baked, brute, 0.005) << "brute-force point-in-capsule coverage " << brute;
    // The plies lie inside their yarn: their projection covers less than the yarn's capsules
    // (one ply on the centreline with the yarn's radius is the yarn itself), but most of it.
    PlyOptions yarn;
    yarn.count = 1;
    const double yarnCoverage = projectedPlyCoverage(bakePlies(p, yarn, true), p.px, p.py, 160);
    EXPECT_LT(baked, yarnCoverage + 0.01);
    EXPECT_GT(baked, 0.7 * yarnCoverage);
    // Some pixels are holes or partly covered: the coverage map is not all 0 or 1.
    EXPECT_TRUE(std::any_of(b.coverage.begin(), b.coverage.end(), [](float c) { return c > 0 && c < 1; }));
}

// A placement that stretches the pattern (a square period on the mesh squeezes the stockinette's
// wide stitch across) is baked as the cell lies on the mesh: the period and the texture's aspect
// follow the stretch, and the coverage is the brute-force coverage of the stretched pattern's
// plies, not the unstretched one's.
TEST(Bake, stretchedPlacementBakesTheCellAsItLiesOnTheMesh) {
    const Pattern p = generateStockinette();
    PatternPlacement square;
    square.periodMetres = {0.01, 0.01};
    const glm::dvec2 stretch = placementStretch(p, square);
    EXPECT_NEAR(stretch.x * stretch.y, 1.0, 1e-12) << "area kept";
    EXPECT_NEAR(stretch.x / stretch.y, p.py / p.px, 1e-12);
    BakeOptions o = smallBake();
    o.albedoPaths = 0;
    o.samplesPerAxis = 4;
    const double plain = bakeSurface(p, o).meanCoverage();
    o.stretch[0] = stretch.x, o.stretch[1] = stretch.y;
    const SurfaceBake b = bakeSurface(p, o);
    EXPECT_DOUBLE_EQ(b.period[0], stretch.x * p.px);
    EXPECT_DOUBLE_EQ(b.period[1], stretch.y * p.py);
    EXPECT_EQ(b.height, b.width) << "a square period gives a square texture";
    Pattern q = p;
    for (glm::dvec3& v : q.points) v.x *= stretch.x, v.y *= stretch.y;
    q.px *= stretch.x, q.py *= stretch.y;
    const double brute = projectedPlyCoverage(bakePlies(q, o.plies, true), q.px, q.py, 160);
    std::printf("coverage: stretched %.4f (brute force %.4f), unstretched %.4f\n", b.meanCoverage(), brute, plain);
    EXPECT_NEAR(b.meanCoverage(), brute, 0.005);
    EXPECT_GT(std::abs(b.meanCoverage() - plain), 0.02);
    o.stretch[0] = 0;
    EXPECT_NE(test::errorOf([&] { bakeSurface(p, o); }).find("stretch"), std::string::npos);
}

TEST(Bake, heightNormalAndAlbedoStayInRange) {
    const SurfaceBake b = bakeSurface(generateStockinette(), smallBake());
    for (size_t i = 0; i < b.coverage.size(); ++i) {
        EXPECT_GE(b.heights[i], 0.f);
        EXPECT_LE(b.heights[i], 1.f);
        const glm::dvec3 n(b.normal[3 * i], b.normal[3 * i + 1], b.normal[3 * i + 2]);
        EXPECT_NEAR(glm::length(n), 1.0, 1e-4);
        EXPECT_GT(n.z, -1e-6) << "a normal seen from above points up";
        for (int c = 0; c < 3; ++c) EXPECT_LE(b.albedo[3 * i + c], 1.f);
    }
    // The body colour is reddish brown (0.55, 0.32, 0.18): the baked albedo keeps its order.
    double r = 0, g = 0, bl = 0;
    for (size_t i = 0; i < b.coverage.size(); ++i)
        r += b.albedo[3 * i], g += b.albedo[3 * i + 1], bl += b.albedo[3 * i + 2];
    EXPECT_GT(r, g);
    EXPECT_GT(g, bl);
    EXPECT_EQ(baseColorRgba8(b).size(), 4 * b.coverage.size());
}

// The transmittance (light from a white sky below that comes up through the yarn) is in [0, 1],
// keeps the body colour's order, is less than the albedo (the yarn is seen from the lit side:
// most light scatters back up), and with the albedo no more than the light that came in, at
// every pixel (the BSDF conserves energy; the bake clamps what a few paths overshoot).
TEST(Bake, transmittanceIsTheLightThroughTheYarnAndConservesEnergy) {
    BakeOptions o = smallBake();
    o.albedoPaths = 8;
    const SurfaceBake b = bakeSurface(generateStockinette(), o);
    ASSERT_EQ(b.transmittance.size(), b.albedo.size());
    Rgb t(0.0), a(0.0);
    double covered = 0;
    for (size_t i = 0; i < b.coverage.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(b.transmittance[3 * i + c], 0.f);
            EXPECT_LE(b.albedo[3 * i + c] + b.transmittance[3 * i + c], 1.f + 1e-6f) << "pixel " << i;
            t[c] += b.coverage[i] * b.transmittance[3 * i + c];
            a[c] += b.coverage[i] * b.albedo[3 * i + c];
        }
        covered += b.coverage[i];
    }
    ASSERT_GT(covered, 0);
    t /= covered, a /= covered;
    std::printf("mean albedo %.4f %.4f %.4f, transmittance %.4f %.4f %.4f\n", a.r, a.g, a.b, t.r, t.g, t.b);
    EXPECT_GT(t.r, 0.01) << "the reddish body lets red light through";
    EXPECT_GT(t.r, t.g);
    EXPECT_GT(t.g, t.b);
    for (int c = 0; c < 3; ++c) EXPECT_LT(t[c], a[c]) << "channel " << c;
}

// Image orientation: +x to the right, +y up (row 0 is the top). At a yarn's silhouette the normal
// turns away from the yarn, against the coverage gradient: sum n . grad(coverage) < 0 per axis
// (a map flipped in x or y would give a positive sum).
TEST(Bake, normalsTurnAwayFromTheYarnAtItsSilhouette) {
    BakeOptions o = smallBake();
    o.albedoPaths = 0;
    o.samplesPerAxis = 3;
    const SurfaceBake b = bakeSurface(generateStockinette(), o);
    const int w = b.width, h = b.height;
    auto coverage = [&](int c, int r) { return double(b.coverage[size_t((r + h) % h) * w + size_t((c + w) % w)]); };
    double alongX = 0, alongY = 0, weight = 0;
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
            const size_t p = size_t(r) * w + size_t(c);
            if (b.coverage[p] == 0.f) continue;
            const double gx = coverage(c + 1, r) - coverage(c - 1, r), gy = coverage(c, r - 1) - coverage(c, r + 1);
            alongX += b.normal[3 * p] * gx, alongY += b.normal[3 * p + 1] * gy;
            weight += std::abs(gx) + std::abs(gy);
        }
    ASSERT_GT(weight, 0);
    EXPECT_LT(alongX / weight, -0.1);
    EXPECT_LT(alongY / weight, -0.1);
}

TEST(Bake, sameTexturesForAnyThreadCount) {
    const SurfaceBake a = bakeSurface(generateStockinette(), smallBake());
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const SurfaceBake b = bakeSurface(generateStockinette(), smallBake());
    EXPECT_EQ(a.albedo, b.albedo);
    EXPECT_EQ(a.coverage, b.coverage);
}

TEST(Bake, badSizeNamesTheOption) {
    BakeOptions o = smallBake();
    o.width = 0;
    EXPECT_NE(test::errorOf([&] { bakeSurface(generateStockinette(), o); }).find("the bake size"), std::string::npos);
}

}  // namespace
}  // namespace knit
