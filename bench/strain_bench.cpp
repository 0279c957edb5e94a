// strain_bench.cpp — strain-aware deformation (docs/deformation.md): making the default pattern's
// 9 x 9 x 9 strain table, and one strain-aware frame against a geometric one.
//
// StrainTable: makeStrainTable(stockinette), counters wallSeconds and cpuSeconds (process CPU;
// the machine is shared, so the CPU time is the steadier number).
// StrainFrame: the built-in drape knitted with stockinette at KNIT_ANIM_REPEATS x KNIT_ANIM_REPEATS
// repeats (default 350: about 3M yarn vertices), bound once with the table; per frame (a travelling
// wave, yarns only) the Animator with the deformer against one without; counters strainOverGeometric
// (wall) and cpuStrainOverGeometric (process CPU, the steadier number on a shared machine), over 5
// and over 20 frames. KNIT_SIMD=0 runs both frames' scalar loops (to compare in one binary).
// BasketweaveSample: one table sample of chart:basketweave (384 cell vertices, the sparse Newton
// systems of docs/deformation.md "400-vertex patterns"): relaxStrainCell from the pattern's own
// cell onto the lattice stretched by 15 % along the courses (one step of the default sx axis);
// counters iterations, converged, cpuSeconds and cpuMsPerIteration (process CPU).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_clock.hpp"
#include "knit/animation.hpp"
#include "knit/generator.hpp"
#include "knit/strain.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::shared_ptr<const knit::StrainTable> stockinetteTable() {
    static const auto table =
        std::make_shared<const knit::StrainTable>(knit::makeStrainTable(knit::generateStockinette(), {}));
    return table;
}

void strainTable(benchmark::State& state) {
    for (auto _ : state) {
        const std::clock_t c0 = std::clock();
        const auto t0 = Clock::now();
        knit::StrainTableStats stats;
        benchmark::DoNotOptimize(knit::makeStrainTable(knit::generateStockinette(), {}, &stats));
        state.counters["wallSeconds"] = since(t0);
        state.counters["cpuSeconds"] = double(std::clock() - c0) / CLOCKS_PER_SEC;
        state.counters["unconverged"] = double(stats.unconverged);
    }
}
BENCHMARK(strainTable)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void basketweaveSample(benchmark::State& state) {
    const knit::Pattern pattern = knit::loadPatternFileOrName("chart:basketweave");
    for (auto _ : state) {
        const double c0 = knit::bench::cpuSeconds();
        const knit::StrainCellResult r = knit::relaxStrainCell(pattern, {0.15, 0, 0}, {});
        const double cpu = knit::bench::cpuSeconds() - c0;
        state.counters["iterations"] = r.iterations;
        state.counters["converged"] = r.converged ? 1 : 0;
        state.counters["cpuSeconds"] = cpu;
        state.counters["cpuMsPerIteration"] = 1e3 * cpu / std::max(1, r.iterations);
    }
}
BENCHMARK(basketweaveSample)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

const knit::Scene& garment() {
    static const knit::Scene scene = [] {
        knit::SceneOptions o;
        const char* env = std::getenv("KNIT_ANIM_REPEATS");
        const double repeats = env ? std::atof(env) : 350.0;
        o.placement.repeats = {repeats, repeats};
        o.buildPlies = false;
        o.deform = {knit::DeformMode::Strain, stockinetteTable()};
        return buildScene(knit::generateStockinette(), knit::makeDrape(), o);
    }();
    return scene;
}

void strainFrame(benchmark::State& state) {
    const knit::Scene& rest = garment();
    knit::AnimatorOptions o;
    o.plies = false;
    o.stats = false;
    const knit::Animator strain(rest, o);
    o.deform = false;
    const knit::Animator geometric(rest, o);
    knit::AnimationFrame a, b;
    double tStrain = 0, tGeometric = 0, cStrain = 0, cGeometric = 0;  // wall and process CPU seconds
    int k = 0;
    for (auto _ : state) {
        std::vector<glm::dvec3> p = rest.mesh().positions;
        for (glm::dvec3& q : p) q.z += 0.01 * std::sin(20.0 * q.x + 0.2 * k);
        ++k;
        auto t0 = Clock::now();
        std::clock_t c0 = std::clock();
        strain.evaluate(p, a);
        tStrain += since(t0);
        cStrain += double(std::clock() - c0) / CLOCKS_PER_SEC;
        t0 = Clock::now();
        c0 = std::clock();
        geometric.evaluate(p, b);
        tGeometric += since(t0);
        cGeometric += double(std::clock() - c0) / CLOCKS_PER_SEC;
    }
    state.counters["yarnVertices"] = double(rest.yarns().curves.pointCount());
    state.counters["strainSeconds"] = tStrain / k;
    state.counters["geometricSeconds"] = tGeometric / k;
    state.counters["strainOverGeometric"] = tStrain / tGeometric;
    state.counters["strainCpuSeconds"] = cStrain / k;
    state.counters["geometricCpuSeconds"] = cGeometric / k;
    state.counters["cpuStrainOverGeometric"] = cStrain / cGeometric;
    state.counters["clampedFraction"] = a.deform.total ? double(a.deform.clamped) / double(a.deform.total) : 0.0;
}
// 5 frames (the first one's page faults on both output buffers included) and 20 (closer to a
// sequence's steady state): filter strainFrame runs both on one scene.
BENCHMARK(strainFrame)->Iterations(5)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(strainFrame)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
