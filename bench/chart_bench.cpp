// Chart relaxation targets of issue 13: a 2 x 2 stockinette in <= 2 s, a 12-stitch x 16-row
// cable cell in <= 60 s (2 cores); issue 25: every built-in of round 2 (lace, slip stitch, tuck,
// stranded, intarsia) in <= 60 s; RelaxOptions::affinePeriod against the default. Counters: iterations, min distance (radii), L r / A.
#include <benchmark/benchmark.h>

#include <string>

#include <glm/geometric.hpp>

#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"

namespace {

double lengthPerArea(const knit::Pattern& p) {
    double L = 0;
    for (const knit::PeriodicEdge& e : p.edges)
        L += glm::length(p.points[e.v1] + glm::dvec3(e.dx * p.px, e.dy * p.py, 0) - p.points[e.v0]);
    return L * p.radius / (p.px * p.py);
}

// 12 stitches x 16 rows: two 2/2 cables (front and back) between purl columns, crossed every
// 8 rows.
std::string cableCell() {
    std::string text;
    for (int row = 15; row >= 0; --row) {
        if (row % 8 == 0) text += "p p c2/2f p p c2/2b\n";
        else text += "p p k k k k p p k k k k\n";
    }
    return text;
}

void relax(benchmark::State& state, const knit::Chart& chart, bool affine = false) {
    knit::ChartPattern cp;
    knit::ChartPatternOptions options;
    options.affinePeriod = affine;
    for (auto _ : state) cp = knit::relaxChart(chart, options);
    state.counters["iterations"] = cp.relaxed.iterations;
    state.counters["evaluations"] = cp.relaxed.evaluations;
    state.counters["pair_rebuilds"] = cp.relaxed.pairRebuilds;
    state.counters["converged"] = cp.relaxed.converged;
    state.counters["min_distance_r"] = cp.relaxed.minDistance;
    state.counters["L_r_per_A"] = lengthPerArea(cp.relaxed.pattern);
    state.counters["vertices"] = double(cp.relaxed.pattern.points.size());
}

void BM_RelaxStockinette2x2(benchmark::State& state) { relax(state, knit::builtinChart("chart:stockinette")); }
void BM_RelaxCable12x16(benchmark::State& state) { relax(state, knit::parseChart(cableCell(), "cable12x16")); }

void BM_RelaxBuiltin(benchmark::State& state, const char* name) { relax(state, knit::builtinChart(name)); }
// RelaxOptions::affinePeriod (faster, for previews; off by default).
void BM_RelaxAffineStockinette2x2(benchmark::State& state) {
    relax(state, knit::builtinChart("chart:stockinette"), true);
}
void BM_RelaxAffineCable12x16(benchmark::State& state) {
    relax(state, knit::parseChart(cableCell(), "cable12x16"), true);
}
void BM_RelaxAffineBuiltin(benchmark::State& state, const char* name) { relax(state, knit::builtinChart(name), true); }

}  // namespace

BENCHMARK_CAPTURE(BM_RelaxBuiltin, eyelet_mesh, "chart:eyelet-mesh")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxBuiltin, honeycomb, "chart:honeycomb")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxBuiltin, fishermans_rib, "chart:fishermans-rib")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxBuiltin, fair_isle, "chart:fair-isle")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxBuiltin, intarsia_blocks, "chart:intarsia-blocks")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxAffineBuiltin, eyelet_mesh, "chart:eyelet-mesh")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_RelaxAffineBuiltin, intarsia_blocks, "chart:intarsia-blocks")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_RelaxStockinette2x2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelaxAffineStockinette2x2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelaxCable12x16)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_RelaxAffineCable12x16)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();
