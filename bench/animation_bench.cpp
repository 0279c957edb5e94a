// animation_bench.cpp — per-frame throughput of the Animator against a full build.
//
// Input: the built-in drape mesh knitted with stockinette at KNIT_ANIM_REPEATS x KNIT_ANIM_REPEATS
// repeats (default 350: about 3M yarn vertices, the garment), bound once; frames are
// the mesh under a travelling wave (in memory: no file reading or writing).
// Counters (per frame, wall clock, all cores):
//   yarnVerticesPerSecond   binding evaluation (Animator stage "evaluate")
//   plyVerticesPerSecond    resampling with the fixed layout + frames + helices
//   frameOverBuild          Animator::evaluate (with plies and stats) / buildScene of that frame
//   frameWithoutStatsOverBuild  the same without the frame statistics (statsSeconds)
//   residentGrowthBytes     resident memory after frame 10 minus after frame 2 (flat: ~0)
//   plyVerticesPerCpuSecond resampling + frames + helices per second of process CPU time (all
//                           threads; the machine is shared, so this is the comparable rate): the
//                           median CPU time of a frame with plies minus one without (no stats)
#include "bench_clock.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "knit/animation.hpp"
#include "knit/generator.hpp"
#include "util/platform.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

using knit::bench::cpuSeconds;
using knit::bench::median;

knit::SceneOptions garmentOptions() {
    knit::SceneOptions o;
    const char* env = std::getenv("KNIT_ANIM_REPEATS");
    const double repeats = env ? std::atof(env) : 350.0;
    o.placement.repeats = {repeats, repeats};
    o.buildPlies = false;
    return o;
}

// The Animator's options with the frames' precision from KNIT_PLY_PRECISION ("double" or
// "float"; unset: the Animator's default), to compare the two in one binary.
knit::AnimatorOptions animatorOptions() {
    knit::AnimatorOptions o;
    if (const char* env = std::getenv("KNIT_PLY_PRECISION"))
        o.framePrecision = std::string(env) == "float" ? knit::FramePrecision::Float32 : knit::FramePrecision::Double;
    return o;
}

const knit::Scene& garment() {
    static const knit::Scene scene = buildScene(knit::generateStockinette(), knit::makeDrape(), garmentOptions());
    return scene;
}

std::vector<glm::dvec3> waveFrame(const knit::BaseMesh& mesh, int k) {
    std::vector<glm::dvec3> p = mesh.positions;
    for (glm::dvec3& q : p) q.z += 0.01 * std::sin(20.0 * q.x + 0.2 * k);
    return p;
}

void animationFrame(benchmark::State& state) {
    const knit::Scene& rest = garment();
    const knit::Animator animator(rest, animatorOptions());
    knit::AnimationFrame frame;
    std::vector<double> evaluate, plies, whole, normals, stats;
    size_t residentAt2 = 0, residentAt10 = 0;
    int k = 0;
    for (auto _ : state) {
        const std::vector<glm::dvec3> p = waveFrame(rest.mesh(), k);
        knit::AnimationStageTimes t;
        const auto t0 = Clock::now();
        animator.evaluate(p, frame, &t);
        whole.push_back(since(t0));
        evaluate.push_back(t.evaluate);
        plies.push_back(t.resample + t.plies);
        normals.push_back(t.normals);
        stats.push_back(t.stats);
        if (++k == 2) residentAt2 = knit::util::residentBytes();
        if (k == 10) residentAt10 = knit::util::residentBytes();
    }
    std::sort(evaluate.begin(), evaluate.end());
    std::sort(plies.begin(), plies.end());
    std::sort(whole.begin(), whole.end());
    std::sort(normals.begin(), normals.end());
    std::sort(stats.begin(), stats.end());
    state.counters["normalsSeconds"] = normals[normals.size() / 2];
    state.counters["statsSeconds"] = stats[stats.size() / 2];
    const double yarnVertices = double(rest.yarns().curves.pointCount());
    state.counters["yarnVertices"] = yarnVertices;
    state.counters["plyVertices"] = double(animator.plyPointCount());
    state.counters["yarnVerticesPerSecond"] = yarnVertices / evaluate[evaluate.size() / 2];
    state.counters["plyVerticesPerSecond"] = double(animator.plyPointCount()) / plies[plies.size() / 2];
    state.counters["medianFrameSeconds"] = whole[whole.size() / 2];

    // Process CPU time of the plies: frames with plies (no stats) minus frames without.
    knit::AnimatorOptions withPlies = animatorOptions(), withoutPlies = animatorOptions();
    withPlies.stats = withoutPlies.stats = withoutPlies.plies = false;
    withPlies.plies = true;
    const knit::Animator plyAnimator(rest, withPlies), yarnAnimator(rest, withoutPlies);
    std::vector<double> cpuWith, cpuWithout;
    for (int f = 0; f < 7; ++f) {
        const std::vector<glm::dvec3> p = waveFrame(rest.mesh(), f);
        double c0 = cpuSeconds();
        plyAnimator.evaluate(p, frame);
        cpuWith.push_back(cpuSeconds() - c0);
        c0 = cpuSeconds();
        yarnAnimator.evaluate(p, frame);
        cpuWithout.push_back(cpuSeconds() - c0);
    }
    state.counters["plyCpuSeconds"] = median(cpuWith) - median(cpuWithout);
    state.counters["plyVerticesPerCpuSecond"] =
        double(animator.plyPointCount()) / (median(cpuWith) - median(cpuWithout));
    if (k >= 10) state.counters["residentGrowthBytes"] = double(residentAt10) - double(residentAt2);

    // One full build of a frame at equal settings (with plies), for the ratio.
    knit::BaseMesh mesh = rest.mesh();
    mesh.positions = waveFrame(rest.mesh(), 3);
    knit::SceneOptions o = garmentOptions();
    o.buildPlies = true;
    const auto t0 = Clock::now();
    const knit::Scene built = buildScene(knit::generateStockinette(), mesh, o);
    const double build = since(t0);
    benchmark::DoNotOptimize(built.plies().curves.points.data());
    state.counters["buildSeconds"] = build;
    state.counters["frameOverBuild"] = whole[whole.size() / 2] / build;
    state.counters["frameWithoutStatsOverBuild"] = (whole[whole.size() / 2] - stats[stats.size() / 2]) / build;
}
BENCHMARK(animationFrame)->Iterations(12)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
