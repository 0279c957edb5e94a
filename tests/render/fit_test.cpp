// Material fit (knit/fit.hpp): recovery of the body albedo on synthetic targets rendered with known
// materials (a light wool, a dark glossy yarn), a uniform target no material matches, the loss,
// the energy-conserving parameter box and bad input. Tiny images, few samples, cheap fiber tables:
// the full-size recovery targets are measured in bench/fit_bench.cpp.
#ifdef KNIT_HAVE_FIT
#include <gtest/gtest.h>

#include <random>

#include "knit/error.hpp"
#include "knit/fit.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"
#include "knit/synthetic_scene.hpp"
#include "fit/fit_renderer.hpp"

namespace knit {
namespace {

// Five wavy courses of three plies on a 1 cm square.
Scene smallCloth() {
    SyntheticSceneOptions o;
    o.courses = 5, o.yarnRadius = 0.0008, o.plyCount = 3, o.waveAmplitude = 0.0004, o.waveLength = 0.006;
    return makeSyntheticPlyScene(o);
}

// 32 x 24, 16 spp, small fiber tables: a render takes milliseconds.
RenderOptions tinyRender(const PlyMaterial& m, uint64_t seed) {
    RenderOptions o;
    o.width = 32, o.height = 24, o.spp = 16, o.seed = seed, o.progress = false;
    o.material = m;
    o.material.tableSize = 64, o.material.aoRays = 64;
    return o;
}

FitTarget target(const Scene& scene, const PlyMaterial& m, LightPlacement light, const char* name) {
    RenderOptions o = tinyRender(m, 11);  // another seed than the fit's: the targets carry their own noise
    o.spp = 64;                           // but less of it, as a photograph would
    o.light = light;
    return {renderScene(scene, o).image, name, false};
}

// Fits only the body albedo, starting from a mid grey, with the true specular lobes, and checks
// every channel is recovered within `tolerance`.
FitResult expectBodyAlbedoRecovered(const PlyMaterial& truth, double tolerance) {
    const Scene scene = smallCloth();
    PlyMaterial start = truth;
    start.bodyAlbedo = Rgb(0.25);  // grey, valid with either specular weight
    FitOptions o;
    o.render = tinyRender(start, 1);
    o.parameters = parseFitList("body-albedo");
    o.maxEvaluations = 80;
    const FitResult r = fitMaterial(scene, target(scene, truth, LightPlacement::Front, "front"),
                                    target(scene, truth, LightPlacement::Back, "back"), {}, o);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.material.bodyAlbedo[c], truth.bodyAlbedo[c], tolerance) << "channel " << c;
    EXPECT_LE(r.renders, 2 * o.maxEvaluations);  // two renders per evaluation, no more
    return r;
}

TEST(Fit, recoversBodyAlbedoOfLightWool) {
    PlyMaterial wool;
    wool.bodyAlbedo = Rgb(0.78, 0.72, 0.6);
    wool.kR = Rgb(0.15), wool.kTT = Rgb(0.1), wool.alphaAlong = wool.alphaAcross = 0.6;
    const FitResult r = expectBodyAlbedoRecovered(wool, 0.05);
    EXPECT_GT(r.front.ssim, 0.8);
    EXPECT_TRUE(r.warnings.empty());
}

TEST(Fit, recoversBodyAlbedoOfDarkGlossyYarn) {
    PlyMaterial glossy;
    glossy.bodyAlbedo = Rgb(0.12, 0.07, 0.05);
    glossy.kR = Rgb(0.7), glossy.kTT = Rgb(0.2), glossy.alphaAlong = glossy.alphaAcross = 0.15;
    expectBodyAlbedoRecovered(glossy, 0.03);
}

TEST(Fit, rendererReusingTheSceneMatchesRenderSceneExactly) {
    const Scene scene = smallCloth();
    RenderOptions o = tinyRender({}, 3);
    FitRenderer renderer(scene, o);
    PlyMaterial other = o.material;
    other.kR = Rgb(0.4), other.fiberShadowFloor = 0.2, other.fiberTwist = -2.0;  // new tables and geometry
    for (const PlyMaterial& m : {o.material, other, o.material})
        for (LightPlacement light : {LightPlacement::Front, LightPlacement::Back}) {
            RenderOptions ro = o;
            ro.material = m, ro.light = light;
            EXPECT_EQ(renderer.render(m, light, 32, 24, 16).rgb, renderScene(scene, ro).image.rgb);
        }
}

TEST(Fit, solidColourTargetEndsWithWarningAndBestFit) {
    const Scene scene = smallCloth();
    Image grey;
    grey.width = 32, grey.height = 24;
    grey.rgb.assign(3 * 32 * 24, 0.2f);
    FitOptions o;
    o.render = tinyRender({}, 1);
    o.maxEvaluations = 8;
    const FitResult r = fitMaterial(scene, {grey, "front 'grey'"}, {grey, "back 'grey'"}, {}, o);
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings[0].find("uniform"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[0].find("front 'grey'"), std::string::npos) << r.warnings[0];
    EXPECT_NO_THROW(validateMaterial(r.material));
    EXPECT_EQ(r.frontRender.width, 32);
    EXPECT_LE(r.renders, 16);
    // The best fit is the best evaluation of the full stage.
    double best = 1e300;
    for (const FitIteration& it : r.history)
        if (it.stage == 1) best = std::min(best, it.loss);
    EXPECT_DOUBLE_EQ(r.loss, best);
}

TEST(Fit, budgetUsedUpByTheCoarseStageStillEndsWithAFullSizeFit) {
    const Scene scene = smallCloth();
    const FitTarget f = target(scene, {}, LightPlacement::Front, "front"),
                    b = target(scene, {}, LightPlacement::Back, "back");
    FitOptions o;
    o.render = tinyRender({}, 1);
    o.budgetSeconds = 1e-6;
    const FitResult r = fitMaterial(scene, f, b, {}, o);
    EXPECT_EQ(r.frontRender.width, 32);
    EXPECT_EQ(r.backRender.height, 24);
    ASSERT_FALSE(r.history.empty());
    EXPECT_EQ(r.history.back().stage, 1);
    EXPECT_LE(r.renders, 6);  // one coarse evaluation at most, then one full-size one
}

TEST(Fit, mismatchedImageSizesNameTheBackImage) {
    Image a, b;
    a.width = 32, a.height = 24, a.rgb.assign(3 * 32 * 24, 0.1f);
    b.width = 30, b.height = 24, b.rgb.assign(3 * 30 * 24, 0.1f);
    try {
        checkFitTargets({a, "--front 'f.png'"}, {b, "--back 'b.png'"}, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--back 'b.png' is 30 x 24"), std::string::npos) << e.what();
    }
    EXPECT_THROW(checkFitTargets({a, "f"}, {a, "b"}, std::vector<float>(10, 1.f)), Error);
}

TEST(Fit, boundsThatBreakEnergyConservationNameTheSetting) {
    std::vector<FitParameter> p = parseFitList("kR,body-albedo");
    applyFitBound(p, "kR=0:0.9");
    applyFitBound(p, "body-albedo=0.3:1");
    try {
        FitSpace(p, PlyMaterial{});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the parameter bounds"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("energy bound"), std::string::npos) << e.what();
    }
    // Fixed fields count too: kTT up to 0.8 with the default body albedo 0.55 breaks it.
    EXPECT_THROW(FitSpace({{"kTT", 0, 0.8}}, PlyMaterial{}), Error);
    EXPECT_THROW(applyFitBound(p, "kR=0:1.5"), Error);
    EXPECT_THROW(applyFitBound(p, "kR=0.5:0.2"), Error);
    EXPECT_THROW(applyFitBound(p, "kTT=0:0.5"), Error);  // not a fitted field
    EXPECT_THROW(parseFitList("kR,glossiness"), Error);
    EXPECT_THROW(parseFitList("kR,kR"), Error);
}

TEST(Fit, everyPointOfTheBoxIsAnEnergyConservingMaterial) {
    const FitSpace space(parseFitList("kR,kTT,body-albedo,reflect-fraction,alpha-along"), PlyMaterial{});
    ASSERT_EQ(space.size(), 7u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 200; ++k) {
        std::vector<double> x(space.size());
        for (double& v : x) v = k == 0 ? 1.0 : u(rng);  // the all-ones corner first
        const PlyMaterial m = space.material(x);
        EXPECT_NO_THROW(validateMaterial(m)) << k;
        const std::vector<double> back = space.vector(m);
        for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(back[i], x[i], 1e-9) << k << " " << i;
    }
}

TEST(Fit, lossIsZeroForTheSameImageAndIgnoresMaskedPixels) {
    Image a;
    a.width = 16, a.height = 12;
    a.rgb.resize(3 * 16 * 12);
    for (size_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] = float(i % 7) * 0.1f;
    const ImageLoss same = imageLoss(a, a, {});
    EXPECT_DOUBLE_EQ(same.total, 0);
    EXPECT_NEAR(same.ssim, 1, 1e-12);
    Image b = a;
    b.rgb[0] = 5.f;  // pixel 0 differs
    EXPECT_GT(imageLoss(b, a, {}).total, 0.01);
    std::vector<float> mask(16 * 12, 1.f);
    mask[0] = 0;
    EXPECT_NEAR(imageLoss(b, a, mask).rmse, 0, 1e-12);
    // An 8-bit target saturates: a render above 1 where the target is 1 is no error.
    Image white = a, bright = a;
    for (float& v : white.rgb) v = 1.f;
    for (float& v : bright.rgb) v = 3.f;
    LossOptions sat;
    sat.saturate = true;
    EXPECT_NEAR(imageLoss(bright, white, {}, sat).total, 0, 1e-12);
}

}  // namespace
}  // namespace knit
#endif  // KNIT_HAVE_FIT
