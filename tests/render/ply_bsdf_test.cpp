// Ply BSDF tests as trusted renderers run them: chi-square of sample() against pdf(), white
// furnace, reciprocity, sample weights; plus the fiber tables and material validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include <boost/math/special_functions/gamma.hpp>
#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/ply_bsdf.hpp"
#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace knit {
namespace {

constexpr double kPi = 3.14159265358979323846;

PlyMaterial anisotropicMaterial() {
    PlyMaterial m;
    m.alphaAlong = 0.3;
    m.alphaAcross = 0.55;
    m.kR = Rgb(0.5, 0.45, 0.4);
    m.alphaTT = 0.8;
    m.kTT = Rgb(0.3);
    m.bodyAlbedo = Rgb(0.4, 0.3, 0.2);
    m.reflectFraction = 0.6;
    return m;
}

PlyMaterial specularMaterial() {
    PlyMaterial m;
    m.alphaAlong = 0.25;
    m.alphaAcross = 0.35;
    m.kR = Rgb(0.9);
    m.alphaTT = 0.5;
    m.kTT = Rgb(0.9);
    m.bodyAlbedo = Rgb(0.1);
    m.reflectFraction = 0.3;
    return m;
}

std::vector<glm::dvec3> incidentDirections() {
    const double s45 = std::sqrt(0.5);
    return {glm::dvec3(0, 0, 1),                                        // normal
            glm::dvec3(s45 * std::cos(0.5), s45 * std::sin(0.5), s45),  // 45 degrees
            glm::normalize(glm::dvec3(0.8, 0.3, 0.05)),                 // grazing
            glm::normalize(glm::dvec3(0.3, -0.4, -0.85))};              // below
}

// Chi-square test on the equal-area sphere map (cos theta, phi): histogram of sample() against the
// integral of pdf() per cell; cells with expected < 5 pooled; returns the p-value.
struct Chi2Result {
    double pValue = 1;
    double pdfIntegral = 0;
    int misses = 0;  // samples in cells whose expected count is 0
};

Chi2Result chi2(const PlyBsdf& sampler, const PlyBsdf& bsdf, const glm::dvec3& wo, int samples, uint64_t seed) {
    const int nTheta = 50, nPhi = 100, ires = 8;
    std::vector<double> observed(nTheta * nPhi, 0.0), expected(nTheta * nPhi, 0.0);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    for (int s = 0; s < samples; ++s) {
        const BsdfSample bs = sampler.sample(wo, uni(rng), glm::dvec2(uni(rng), uni(rng)));
        if (!bs.valid) continue;
        const glm::dvec3 w = glm::normalize(bs.wi);
        const int it = std::min(nTheta - 1, static_cast<int>((w.z + 1.0) * 0.5 * nTheta));
        const int ip = std::min(nPhi - 1, static_cast<int>((std::atan2(w.y, w.x) + kPi) / (2 * kPi) * nPhi));
        observed[it * nPhi + ip] += 1;
    }
    Chi2Result r;
    const double dz = 2.0 / nTheta, dp = 2 * kPi / nPhi;
    for (int it = 0; it < nTheta; ++it)
        for (int ip = 0; ip < nPhi; ++ip) {
            double sum = 0;
            for (int a = 0; a < ires; ++a)
                for (int b = 0; b < ires; ++b) {
                    const double z = -1.0 + (it + (a + 0.5) / ires) * dz;
                    const double phi = -kPi + (ip + (b + 0.5) / ires) * dp;
                    const double st = std::sqrt(std::max(0.0, 1 - z * z));
                    sum += bsdf.pdf(wo, glm::dvec3(st * std::cos(phi), st * std::sin(phi), z));
                }
            const double integral = sum * dz * dp / (ires * ires);
            r.pdfIntegral += integral;
            expected[it * nPhi + ip] = integral * samples;
        }
    // Pool cells with small expected counts (sorted by expectation).
    std::vector<int> order(expected.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double chsq = 0, pe = 0, po = 0;
    int cells = 0;
    for (int i : order) {
        if (expected[i] == 0) {
            if (observed[i] > 0) r.misses += static_cast<int>(observed[i]);
            continue;
        }
        if (expected[i] < 5) {
            pe += expected[i];
            po += observed[i];
            if (pe >= 5) {
                chsq += (po - pe) * (po - pe) / pe;
                ++cells;
                pe = po = 0;
            }
        } else {
            chsq += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
            ++cells;
        }
    }
    if (pe > 0) {
        chsq += (po - pe) * (po - pe) / pe;
        ++cells;
    }
    const int dof = cells - 1;
    r.pValue = dof >= 1 ? boost::math::gamma_q(dof / 2.0, chsq / 2.0) : 0.0;
    return r;
}

glm::dvec3 uniformSphere(double u1, double u2) {
    const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

void runChi2(const PlyMaterial& m, double shadow) {
    const PlyBsdf bsdf(m, shadow);
    const auto dirs = incidentDirections();
    const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / dirs.size());  // Sidak
    uint64_t seed = 7;
    for (const glm::dvec3& wo : dirs) {
        const Chi2Result r = chi2(bsdf, bsdf, wo, 1000000, seed++);
        EXPECT_EQ(r.misses, 0) << "samples where pdf() is zero, wo.z = " << wo.z;
        EXPECT_LE(r.pdfIntegral, 1.01) << "pdf integrates above one, wo.z = " << wo.z;
        EXPECT_GT(r.pValue, alpha) << "chi-square rejects sample() vs pdf() for wo = (" << wo.x << ", " << wo.y << ", "
                                   << wo.z << ")";
    }
}

TEST(PlyBsdf, chi2SamplingMatchesPdfAnisotropicIncludingGrazingAndBelow) { runChi2(anisotropicMaterial(), 0.7); }

TEST(PlyBsdf, chi2SamplingMatchesPdfSpecularDominated) { runChi2(specularMaterial(), 1.0); }

TEST(PlyBsdf, chi2DetectsAWrongPdf) {
    // The test must be able to fail: samples of one material against the pdf of a slightly
    // rougher one are rejected, while the same pair passes.
    PlyMaterial a = specularMaterial(), b = a;
    b.alphaAlong = 0.4;
    const PlyBsdf sa(a), pb(b);
    const glm::dvec3 wo = incidentDirections()[1];
    EXPECT_GT(chi2(sa, sa, wo, 400000, 11).pValue, 1e-3);
    EXPECT_LT(chi2(sa, pb, wo, 400000, 11).pValue, 1e-6);
}

TEST(PlyBsdf, whiteFurnaceAlbedoAtMostOne) {
    // Materials on the energy bound max(kR, kTT) + rho_B = 1, low and high roughness.
    std::vector<PlyMaterial> mats;
    for (double alpha : {0.05, 0.3, 0.9}) {
        PlyMaterial m;
        m.alphaAlong = alpha;
        m.alphaAcross = std::min(1.0, alpha * 1.5);
        m.alphaTT = alpha;
        m.kR = Rgb(0.7);
        m.kTT = Rgb(0.7);
        m.bodyAlbedo = Rgb(0.3);
        mats.push_back(m);
    }
    mats.push_back(anisotropicMaterial());
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    for (const PlyMaterial& m : mats) {
        const PlyBsdf bsdf(m, 1.0);
        for (int k = 0; k < 12; ++k) {
            const glm::dvec3 wo = uniformSphere(uni(rng), uni(rng));
            Rgb sum(0.0);
            const int n = 40000;
            for (int s = 0; s < n; ++s) {
                const BsdfSample bs = bsdf.sample(wo, uni(rng), glm::dvec2(uni(rng), uni(rng)));
                if (bs.valid) sum += bs.weight;
            }
            const Rgb albedo = sum / double(n);
            for (int c = 0; c < 3; ++c) EXPECT_LE(albedo[c], 1.01) << "alpha " << m.alphaAlong << " wo.z " << wo.z;
        }
    }
}

TEST(PlyBsdf, whiteFurnaceLosslessBodyIsOneWithinNoise) {
    // No specular lobes, rho_B = 1, no shadow: every direction scatters all energy.
    PlyMaterial m;
    m.kR = Rgb(0.0);
    m.kTT = Rgb(0.0);
    m.bodyAlbedo = Rgb(1.0);
    m.reflectFraction = 0.35;
    const PlyBsdf bsdf(m, 1.0);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    for (const glm::dvec3& wo : incidentDirections()) {
        // Uniform-sphere estimator: independent of the sampling code.
        const int n = 400000;
        double sum = 0, sum2 = 0;
        for (int s = 0; s < n; ++s) {
            const glm::dvec3 wi = uniformSphere(uni(rng), uni(rng));
            const double v = bsdf.eval(wo, wi).x * std::abs(wi.z) * 4 * kPi;
            sum += v;
            sum2 += v * v;
        }
        const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, 1.0, 4 * sigma + 1e-9) << "wo.z " << wo.z;
        // Importance-sampled: every weight is exactly one.
        for (int s = 0; s < 1000; ++s) {
            const BsdfSample bs = bsdf.sample(wo, uni(rng), glm::dvec2(uni(rng), uni(rng)));
            ASSERT_TRUE(bs.valid);
            EXPECT_NEAR(bs.weight.x, 1.0, 1e-9);
        }
    }
}

TEST(PlyBsdf, importanceAndUniformEstimatesAgree) {
    const PlyBsdf bsdf(anisotropicMaterial(), 0.8);
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    for (const glm::dvec3& wo : incidentDirections()) {
        double is = 0, un = 0;
        const int n = 200000;
        for (int s = 0; s < n; ++s) {
            const BsdfSample bs = bsdf.sample(wo, uni(rng), glm::dvec2(uni(rng), uni(rng)));
            if (bs.valid) is += luminance(bs.weight);
            const glm::dvec3 wi = uniformSphere(uni(rng), uni(rng));
            un += luminance(bsdf.eval(wo, wi)) * std::abs(wi.z) * 4 * kPi;
        }
        EXPECT_NEAR(is / n, un / n, 0.05 * (un / n)) << "wo.z " << wo.z;
    }
}

TEST(PlyBsdf, reciprocityHoldsForAllLobes) {
    const PlyBsdf bsdf(anisotropicMaterial(), 0.6);
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    double maxF = 0;
    std::vector<std::pair<Rgb, Rgb>> pairs;
    for (int k = 0; k < 20000; ++k) {
        const glm::dvec3 a = uniformSphere(uni(rng), uni(rng)), b = uniformSphere(uni(rng), uni(rng));
        const Rgb fab = bsdf.eval(a, b), fba = bsdf.eval(b, a);
        maxF = std::max({maxF, fab.x, fab.y, fab.z});
        pairs.emplace_back(fab, fba);
    }
    for (const auto& [fab, fba] : pairs)
        for (int c = 0; c < 3; ++c) ASSERT_LE(std::abs(fab[c] - fba[c]), 1e-4 * maxF);
}

TEST(PlyBsdf, sampleWeightEqualsFCosOverPdf) {
    const PlyBsdf bsdf(specularMaterial(), 0.5);
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    int valid = 0;
    for (int k = 0; k < 50000; ++k) {
        const glm::dvec3 wo = uniformSphere(uni(rng), uni(rng));
        const BsdfSample bs = bsdf.sample(wo, uni(rng), glm::dvec2(uni(rng), uni(rng)));
        if (!bs.valid) continue;
        ++valid;
        const double pdf = bsdf.pdf(wo, bs.wi);
        ASSERT_GT(pdf, 0);
        ASSERT_NEAR(bs.pdf, pdf, 1e-9 * pdf);
        const Rgb expect = bsdf.eval(wo, bs.wi) * std::abs(bs.wi.z) / pdf;
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(bs.weight[c], expect[c], 1e-3 * std::max(1e-12, expect[c]));
        // Lobe side: R / BR stay on the side of wo, TT / BT cross it.
        const bool same = bs.wi.z * wo.z > 0;
        ASSERT_EQ(same, bs.lobe == PlyBsdf::R || bs.lobe == PlyBsdf::BodyR);
    }
    EXPECT_GT(valid, 40000);  // VNDF reflections below the horizon are lost
}

TEST(PlyBsdf, transmissionPeaksStraightThrough) {
    // TT is the GGX lobe mirrored through the surface plane: maximal at wi = -wo.
    PlyMaterial m;
    m.kR = Rgb(0);
    m.kTT = Rgb(1);
    m.bodyAlbedo = Rgb(0);
    m.alphaTT = 0.3;
    const PlyBsdf bsdf(m);
    const glm::dvec3 wo = glm::normalize(glm::dvec3(0.3, 0.2, 0.9));
    const double straight = bsdf.eval(wo, -wo).x;
    const glm::dvec3 u = glm::normalize(glm::cross(wo, glm::dvec3(0, 0, 1))), v = glm::cross(wo, u);
    for (int k = 0; k < 16; ++k) {
        const double a = 2 * kPi * k / 16;
        const glm::dvec3 wi = glm::normalize(-wo + 0.1 * (std::cos(a) * u + std::sin(a) * v));
        EXPECT_LT(bsdf.eval(wo, wi).x, straight) << "direction " << k;
    }
    EXPECT_GT(straight, 2 * bsdf.eval(wo, glm::normalize(-wo + 0.6 * u)).x);
    EXPECT_EQ(bsdf.eval(wo, wo).x, 0.0);  // no reflection with kR = 0 and no body
}

TEST(FiberTables, deltaAndPhaseVanishAtFiberCentres) {
    FiberTableOptions o;
    o.fiberCount = 10;
    o.size = 1000;  // texel centres (i + 0.5)/1000: a fiber centre at i = 99.5 ... use the nearest
    o.aoRays = 64;
    const FiberTables t = buildFiberTables(o);
    ASSERT_EQ(t.size, 1000);
    EXPECT_NEAR(t.ringRadius + t.fiberRadius, 1.0, 1e-12);
    for (int k = 0; k < 10; ++k) {
        const FiberTables::Texel x = t.fiber((k + 0.0005) / 10.0);
        EXPECT_NEAR(x.delta, 0.0, 0.05);
        EXPECT_NEAR(x.phase, 0.0, 0.02);
    }
    // Between two fibers the visible fiber is offset by up to half the spacing and tilted.
    const FiberTables::Texel mid = t.fiber(0.049);
    EXPECT_GT(std::abs(mid.phase), 0.2);
    EXPECT_GT(std::abs(mid.delta), 0.5);
    // delta is odd around a fiber centre.
    EXPECT_NEAR(t.fiber(0.02).delta, -t.fiber(-0.02 + 1e-4).delta, 0.05);
}

TEST(FiberTables, shadowSpansFloorToOne) {
    FiberTableOptions o;
    o.fiberCount = 20;
    o.plyCount = 3;
    o.size = 256;
    o.aoRays = 256;
    o.fiberShadowFloor = 0.4;
    o.plyShadowFloor = 0.25;
    const FiberTables t = buildFiberTables(o);
    const auto [flo, fhi] = std::minmax_element(t.fiberShadow.begin(), t.fiberShadow.end());
    EXPECT_NEAR(*flo, 0.4, 1e-6);
    EXPECT_NEAR(*fhi, 1.0, 1e-6);
    const auto [plo, phi] = std::minmax_element(t.plyShadow.begin(), t.plyShadow.end());
    EXPECT_NEAR(*plo, 0.25, 1e-6);
    EXPECT_NEAR(*phi, 1.0, 1e-6);
    // The outward side of a ply (phase 0) is less occluded than the side facing the yarn centre.
    EXPECT_GT(t.ply(0.0), t.ply(0.5));
    // A single ply has nothing around it: no ply shadow.
    o.plyCount = 1;
    const FiberTables single = buildFiberTables(o);
    EXPECT_NEAR(single.ply(0.3), 1.0, 1e-6);
}

// A yarn-level curve shows the bundle's ply shadow as seen from outside: darker than the plies'
// outward sides (1), lighter than the table's mean over the whole ply (which includes the faces
// the plies turn to each other, hidden from outside); one ply has none. A yarn-level point takes
// it whatever its phase.
TEST(FiberTables, visiblePlyShadowIsTheBundleSeenFromOutside) {
    FiberTableOptions o;
    o.size = 256, o.aoRays = 256;
    o.plyCount = 1;
    EXPECT_NEAR(buildFiberTables(o).visiblePlyShadow, 1.0, 1e-9);
    for (int plies : {2, 3, 5}) {
        o.plyCount = plies;
        const FiberTables t = buildFiberTables(o);
        double mean = 0;
        for (float v : t.plyShadow) mean += v / t.plyShadow.size();
        std::printf("%d plies: visible ply shadow %.4f, table mean %.4f\n", plies, t.visiblePlyShadow, mean);
        EXPECT_LT(t.visiblePlyShadow, 0.99);
        EXPECT_GT(t.visiblePlyShadow, mean);
        PlySurfacePoint p;
        p.bundle = true;
        PlyMaterial m;
        m.fiberDetail = false;
        for (const glm::dvec3 radial : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0)}) {
            p.radial = radial;
            EXPECT_DOUBLE_EQ(plyShadingFrame(p, m, t).shadow, t.visiblePlyShadow);
        }
    }
}

TEST(FiberTables, shadingFrameIsOrthonormalAndFollowsTwist) {
    PlyMaterial m;
    const FiberTables t = buildFiberTables(fiberTableOptions(m, 2));
    PlySurfacePoint p;
    p.tangent = glm::dvec3(0, 0, 1);
    p.normal = glm::dvec3(1, 0, 0);
    p.radial = glm::dvec3(0, 1, 0);
    for (double v = 0; v < 10; v += 0.37) {
        p.v = v;
        const ShadingFrame f = plyShadingFrame(p, m, t);
        EXPECT_NEAR(glm::length(f.x), 1, 1e-9);
        EXPECT_NEAR(glm::length(f.z), 1, 1e-9);
        EXPECT_NEAR(glm::dot(f.x, f.z), 0, 1e-9);
        EXPECT_NEAR(glm::dot(glm::cross(f.z, f.x), f.y), 1, 1e-9);
        // The fiber helix leans away from the ply axis by atan(ring * |tau_f|) around the ply.
        EXPECT_LT(glm::dot(f.x, p.tangent), 0.99);
        EXPECT_GE(f.shadow, m.fiberShadowFloor * m.plyShadowFloor - 1e-9);
        EXPECT_LE(f.shadow, 1 + 1e-9);
    }
    m.fiberDetail = false;
    const ShadingFrame flat = plyShadingFrame(p, m, t);
    EXPECT_NEAR(glm::dot(flat.x, p.tangent), 1, 1e-12);
    EXPECT_NEAR(glm::dot(flat.z, p.normal), 1, 1e-12);
}

TEST(PlyMaterial, outOfRangeValueNamesTheField) {
    PlyMaterial m;
    m.alphaAcross = 0.0;
    try {
        validateMaterial(m);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("alphaAcross"), std::string::npos) << e.what();
    }
    m = PlyMaterial();
    m.eta = std::nan("");
    EXPECT_THROW(validateMaterial(m), Error);
}

TEST(PlyMaterial, energyViolationIsRejectedPerChannel) {
    PlyMaterial m;
    m.kR = Rgb(0.5, 0.2, 0.2);
    m.kTT = Rgb(0.1);
    m.bodyAlbedo = Rgb(0.6, 0.6, 0.6);  // 0.5 + 0.6 > 1 in the red channel only
    try {
        validateMaterial(m);
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("energy"), std::string::npos) << msg;
        EXPECT_NE(msg.find("channel r"), std::string::npos) << msg;
    }
    m.bodyAlbedo = Rgb(0.5, 0.6, 0.6);
    EXPECT_NO_THROW(validateMaterial(m));
}

TEST(PlyMaterial, jsonUnknownFieldAndWrongTypeAreNamed) {
    try {
        parseMaterialJson(R"({"kR": 0.2, "shinyness": 3})", "m.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "m.json: unknown field 'shinyness'");
    }
    try {
        parseMaterialJson(R"({"bodyAlbedo": "red"})", "m.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bodyAlbedo"), std::string::npos);
    }
    const PlyMaterial m = parseMaterialJson(R"({"kR": [0.1, 0.2, 0.3], "fiberCount": 12, "fiberDetail": false})", "m");
    EXPECT_DOUBLE_EQ(m.kR.z, 0.3);
    EXPECT_EQ(m.fiberCount, 12);
    EXPECT_FALSE(m.fiberDetail);
    EXPECT_EQ(parseMaterialJson(materialJsonText(m), "m").kR, m.kR);
}

TEST(PlyMaterial, textOverridesTheBaseMaterial) {
    PlyMaterial base;
    base.eta = 1.3;
    base.fiberCount = 7;
    const PlyMaterial m = parseMaterialJson(R"({"fiberCount": 9})", "m", base);
    EXPECT_EQ(m.eta, 1.3);
    EXPECT_EQ(m.fiberCount, 9);
    EXPECT_EQ(parseMaterialJson("{}", "m", base).fiberCount, 7);
}

TEST(PlyMaterial, jsonTextRoundTripsEveryFieldExactly) {
    PlyMaterial m;
    m.eta = 1.0 / 3.0 + 1.0;
    m.kTT = Rgb(0.1, 0.2 / 3.0, 0.3);
    m.fiberDetail = false;
    m.fiberTwist = -std::sqrt(2.0);
    m.aoRays = 17;
    const std::string text = materialJsonText(m);
    EXPECT_EQ(materialJsonText(parseMaterialJson(text, "m")), text);
    const PlyMaterial back = parseMaterialJson(text, "m", PlyMaterial{});
    EXPECT_EQ(back.eta, m.eta);
    EXPECT_EQ(back.kTT, m.kTT);
    EXPECT_EQ(back.fiberTwist, m.fiberTwist);
    EXPECT_EQ(back.aoRays, 17);
    EXPECT_FALSE(back.fiberDetail);
}

TEST(PlyMaterial, textErrorsNameTheSource) {
    const auto errorOf = [](const std::string& text) {
        return test::errorOf([&] { parseMaterialJson(text, "material text"); });
    };
    EXPECT_EQ(errorOf("[0.3, 0.4]"), "material text: a material must be a JSON object");
    EXPECT_EQ(errorOf("{\"kR\": 0.3,").rfind("material text: invalid JSON: ", 0), 0u) << errorOf("{\"kR\": 0.3,");
    EXPECT_EQ(errorOf(R"({"tableSize": 1.5})"), "material text: field 'tableSize' must be an integer");
}

TEST(PlyMaterial, fileErrorsNameTheFile) {
    const std::string path = std::string(test::binaryDir()) + "/render_test_bad_material.json";
    {
        std::ofstream out(path);
        out << "{\"kR\": 0.9, \"bodyAlbedo\": 0.5}";
    }
    try {
        loadMaterialFile(path);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("energy"), std::string::npos);
    }
    {
        std::ofstream out(path);
        out << "{\"kR\": ";
    }
    EXPECT_THROW(loadMaterialFile(path), Error);
    std::remove(path.c_str());
    EXPECT_THROW(loadMaterialFile(path + ".missing"), Error);
}

TEST(PlyMaterial, folderGivenAsMaterialFileIsAnError) {
    // A folder opens as a stream on Linux and fails only when read (it escaped as a
    // std::ios_base::failure, i.e. an internal error of the CLI).
    const std::string dir = std::string(test::binaryDir()) + "/render_test_material_folder.json";
    std::filesystem::create_directories(dir);
    try {
        loadMaterialFile(dir);
        FAIL() << "no error for a folder";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(dir), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace knit
