// Material-fit measurements (knit/fit.hpp), one run each (Iterations(1)); details on stderr.
//   <build>/bench/fit_bench --benchmark_filter=Identifiability   # ~1-3 min on 2 cores
//   <build>/bench/fit_bench --benchmark_filter=DefaultScene      # the 160 x 120 fit, <= ~10 min each
// * BM_FitIdentifiability: the small synthetic cloth at 64 x 48, a known material, the fields of
//   KNIT_FIT_FIELDS free (default kR,kTT,body-albedo; docs/fitting.md also runs all nine); the fit
//   is restarted from KNIT_FIT_RESTARTS (default 5) random starts and the spread (max - min) of
//   each recovered field says whether the two images determine it.
// * BM_FitDefaultScene/material:<m>/closeUp:<c>: the scene `knit render` renders by default
//   (stockinette on the drape), framed as render frames it (closeUp:0) or seen from 6 cm above
//   the top of the drape, where plies span pixels (closeUp:1), targets rendered at 160 x 120 with
//   a known material (0: light wool, 1: dark glossy) and seed 101, fitted (kR, kTT, body albedo; seed 1) within KNIT_FIT_BUDGET seconds (default
//   600). Reports the time, the renders, the recovered values and the fit's loss over the noise
//   floor (the loss of the true material rendered with the fit's seed: two seeds of one render).
#include <benchmark/benchmark.h>
#ifdef KNIT_HAVE_FIT  // built without the fit (KNIT_WITH_FIT=OFF): an empty benchmark

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "knit/fit.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"
#include "knit/synthetic_scene.hpp"

namespace {

using namespace knit;

double envOr(const char* name, double fallback) {
    const char* v = std::getenv(name);
    return v ? std::atof(v) : fallback;
}

PlyMaterial lightWool() {
    PlyMaterial m;
    m.bodyAlbedo = Rgb(0.78, 0.72, 0.6);
    m.kR = Rgb(0.15), m.kTT = Rgb(0.1), m.alphaAlong = m.alphaAcross = 0.6;
    return m;
}

PlyMaterial darkGlossy() {
    PlyMaterial m;
    m.bodyAlbedo = Rgb(0.12, 0.07, 0.05);
    m.kR = Rgb(0.7), m.kTT = Rgb(0.2), m.alphaAlong = m.alphaAcross = 0.15;
    return m;
}

FitTarget renderTarget(const Scene& scene, RenderOptions o, const PlyMaterial& m, LightPlacement light) {
    o.material = m, o.light = light, o.seed = 101, o.progress = false;
    return {renderScene(scene, o).image, light == LightPlacement::Front ? "front" : "back", false};
}

// The loss of `m` rendered with the fit's seed against the targets: the Monte Carlo noise floor.
double lossOf(const Scene& scene, const FitOptions& fit, const PlyMaterial& m, const FitTarget& f, const FitTarget& b) {
    FitOptions o = fit;
    o.render.material = m;
    o.maxEvaluations = 1, o.coarseShare = 0, o.progress = nullptr;
    return fitMaterial(scene, f, b, {}, o).loss;
}

void printValues(const char* what, const std::vector<std::string>& labels, const std::vector<double>& v) {
    std::fprintf(stderr, "%s", what);
    for (size_t i = 0; i < v.size(); ++i) std::fprintf(stderr, " %s=%.3f", labels[i].c_str(), v[i]);
    std::fprintf(stderr, "\n");
}

void BM_FitIdentifiability(benchmark::State& state) {
    SyntheticSceneOptions so;
    so.courses = 8, so.size = 0.016, so.yarnRadius = 0.0008, so.plyCount = 3;
    so.waveAmplitude = 0.0004, so.waveLength = 0.006, so.cellSize = 0.25;
    const Scene scene = makeSyntheticPlyScene(so);
    RenderOptions ro;
    ro.width = 64, ro.height = 48, ro.spp = 16;
    PlyMaterial truth = lightWool();
    truth.reflectFraction = 0.6, truth.fiberShadowFloor = 0.4, truth.plyShadowFloor = 0.3, truth.alphaTT = 0.8;
    truth.tableSize = 128, truth.aoRays = 128;
    const FitTarget f = renderTarget(scene, ro, truth, LightPlacement::Front);
    const FitTarget b = renderTarget(scene, ro, truth, LightPlacement::Back);
    FitOptions fit;
    fit.render = ro;
    const char* fields = std::getenv("KNIT_FIT_FIELDS");
    fit.parameters = parseFitList(fields ? fields : "kR,kTT,body-albedo");
    fit.maxEvaluations = int(envOr("KNIT_FIT_EVALUATIONS", 150));
    const FitSpace space(fit.parameters, truth);
    const std::vector<std::string> labels = space.labels();
    printValues("truth  ", labels, space.values(truth));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    std::vector<double> lo(labels.size(), 1e300), hi(labels.size(), -1e300);
    for (auto _ : state) {
        const int restarts = int(envOr("KNIT_FIT_RESTARTS", 5));
        for (int k = 0; k < restarts; ++k) {
            std::vector<double> x(space.size());
            for (double& v : x) v = u(rng);
            fit.render.material = space.material(x);
            const FitResult r = fitMaterial(scene, f, b, {}, fit);
            printValues(("start " + std::to_string(k)).c_str(), labels, space.values(fit.render.material));
            printValues(("fit   " + std::to_string(k)).c_str(), labels, r.values);
            std::fprintf(stderr, "        loss %.4f, %d renders, %.1f s\n", r.loss, r.renders, r.seconds);
            for (size_t i = 0; i < labels.size(); ++i)
                lo[i] = std::min(lo[i], r.values[i]), hi[i] = std::max(hi[i], r.values[i]);
        }
    }
    std::fprintf(stderr, "noise floor loss %.4f\n", lossOf(scene, fit, truth, f, b));
    for (size_t i = 0; i < labels.size(); ++i) {
        state.counters["spread_" + labels[i]] = hi[i] - lo[i];
        std::fprintf(stderr, "spread %-20s %.3f (%.3f .. %.3f)\n", labels[i].c_str(), hi[i] - lo[i], lo[i], hi[i]);
    }
}
BENCHMARK(BM_FitIdentifiability)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The close-up of BM_FitDefaultScene/<material>/1: 6 cm above the top of the drape, where a ply
// spans a few pixels of 160 x 120 (knit fit --eye 0.01 0.2267 0 --target 0 0.1667 0 --up 0 0 -1).
View closeUp(const RenderOptions& ro) {
    View v;
    v.eye = glm::dvec3(0.01, 0.2267, 0.0), v.target = glm::dvec3(0.0, 0.1667, 0.0), v.up = glm::dvec3(0, 0, -1);
    v.fovDegrees = ro.fovDegrees, v.width = ro.width, v.height = ro.height;
    return v;
}

void BM_FitDefaultScene(benchmark::State& state) {
    const Scene scene = buildScene(SceneOptions{});
    const PlyMaterial truth = state.range(0) == 0 ? lightWool() : darkGlossy();
    RenderOptions ro;
    ro.width = 160, ro.height = 120, ro.spp = int(envOr("KNIT_FIT_SPP", 16));
    if (state.range(1) == 1) ro.view = closeUp(ro);
    const FitTarget f = renderTarget(scene, ro, truth, LightPlacement::Front);
    const FitTarget b = renderTarget(scene, ro, truth, LightPlacement::Back);
    FitOptions fit;
    fit.render = ro;
    fit.render.material = truth;
    fit.render.material.bodyAlbedo = Rgb(0.25), fit.render.material.kR = Rgb(0.3), fit.render.material.kTT = Rgb(0.1);
    fit.parameters = parseFitList("kR,kTT,body-albedo");
    fit.budgetSeconds = envOr("KNIT_FIT_BUDGET", 600);
    fit.maxEvaluations = int(envOr("KNIT_FIT_EVALUATIONS", 200));
    fit.progress = [](const FitIteration& it) {
        if (it.evaluation % 10 == 0) std::fprintf(stderr, "evaluation %d loss %.4f\n", it.evaluation, it.loss);
    };
    FitResult r;
    for (auto _ : state) r = fitMaterial(scene, f, b, {}, fit);
    const FitSpace space(fit.parameters, truth);
    const std::vector<double> t = space.values(truth);
    printValues("truth", r.labels, t);
    printValues("fit  ", r.labels, r.values);
    const double floor = lossOf(scene, fit, truth, f, b);
    std::fprintf(stderr, "%s: %.1f s, %d renders, loss %.4f, noise floor %.4f (ratio %.2f)\n", r.stopReason.c_str(),
                 r.seconds, r.renders, r.loss, floor, r.loss / floor);
    state.counters["seconds"] = r.seconds;
    state.counters["renders"] = r.renders;
    state.counters["loss_over_noise"] = r.loss / floor;
    state.counters["front_rmse"] = r.front.rmse;
    state.counters["back_rmse"] = r.back.rmse;
    for (size_t i = 0; i < t.size(); ++i) state.counters["err_" + r.labels[i]] = r.values[i] - t[i];
}
BENCHMARK(BM_FitDefaultScene)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"material", "closeUp"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
#endif  // KNIT_HAVE_FIT

BENCHMARK_MAIN();
