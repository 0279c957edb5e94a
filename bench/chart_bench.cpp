// Chart relaxation targets of issue 13: a 2 x 2 stockinette in <= 2 s, a 12-stitch x 16-row
// cable cell in <= 60 s (2 cores); issue 25: every built-in chart (BM_RelaxBuiltin/NAME, all of
// builtinChartNames()) and the small lace charts that were slow to settle (BM_RelaxLace) in
// <= 60 s with the yarns >= 1.9 r apart; RelaxOptions::affinePeriod against the default.
// Counters: iterations, evaluations, converged, min distance (radii), L r / A, energy and the
// process CPU seconds of one relaxation (all threads; the machine may be shared). Intarsia
// charts whose boundaries move (BM_RelaxIntarsiaCarried, too slow for the unit tests) also count
// the stitches that lose knitting's crossing with the head below (stitches_off, should be 0).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"

#include "../tests/chart/crossings.hpp"
#include "bench_clock.hpp"
#include "pattern_measures.hpp"

namespace {

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

knit::ChartPattern relax(benchmark::State& state, const knit::Chart& chart, bool affine = false) {
    knit::ChartPattern cp;
    knit::ChartPatternOptions options;
    options.affinePeriod = affine;
    double cpu = 0;
    for (auto _ : state) {
        const double start = knit::bench::cpuSeconds();
        cp = knit::relaxChart(chart, options);
        cpu = knit::bench::cpuSeconds() - start;
    }
    state.counters["cpu_s"] = cpu;
    state.counters["energy"] = cp.relaxed.energy;
    state.counters["iterations"] = cp.relaxed.iterations;
    state.counters["evaluations"] = cp.relaxed.evaluations;
    state.counters["pair_rebuilds"] = cp.relaxed.pairRebuilds;
    state.counters["converged"] = cp.relaxed.converged;
    state.counters["min_distance_r"] = cp.relaxed.minDistance;
    state.counters["L_r_per_A"] = knit::bench::lengthPerArea(cp.relaxed.pattern);
    state.counters["vertices"] = double(cp.relaxed.pattern.points.size());
    return cp;
}

// relax, and count the relaxed stitches failing checkStitchEnds (tests/chart/crossings.hpp).
void relaxCountingCrossings(benchmark::State& state, const knit::Chart& chart) {
    const knit::ChartPattern cp = relax(state, chart);
    knit::ChartCell relaxed = cp.cell;
    relaxed.pattern = cp.relaxed.pattern;
    int off = 0;
    for (int r = 0; r < relaxed.height; ++r)
        for (int c = 0; c < relaxed.width; ++c) off += !knit::test::checkStitchEnds(relaxed, r, c).empty();
    state.counters["stitches_off"] = off;
}

void BM_RelaxStockinette2x2(benchmark::State& state) { relax(state, knit::builtinChart("chart:stockinette")); }
void BM_RelaxCable12x16(benchmark::State& state) { relax(state, knit::parseChart(cableCell(), "cable12x16")); }

// Lace charts whose cells settled slowly (a slow narrowing of the period): k3tog and sssk
// between yarn-overs over a plain row.
const char* const kLaceCharts[][2] = {
    {"yo_k3tog_yo_k", "yo k3tog yo k\nk k k k\n"},
    {"k_yo_sssk_yo", "k yo sssk yo\nk k k k\n"},
};

// Intarsia boundaries moving two columns between rows (tests/fuzz_corpus/chart/intarsia_steep_*).
const char* const kCarriedCharts[][2] = {
    {"steep_stripes", "k k k k k k\nk k k k k k\nk k k k k k\nk k k k k k\n\n"
                      "A A A A B B\nA A B B B B\nB B B B A A\nB B A A A A\nA=#f2e8d5 B=#c1121f\nintarsia\n"},
    {"steep_zigzag", "k k k k k k\nk k k k k k\n\nA A A A B B\nA A B B B B\nA=#f2e8d5 B=#c1121f\nintarsia\n"},
};

}  // namespace

int main(int argc, char** argv) {
    const auto seconds = [](benchmark::internal::Benchmark* b) { b->Unit(benchmark::kSecond)->Iterations(1); };
    for (const std::string& name : knit::builtinChartNames()) {
        std::string label = name.substr(name.find(':') + 1);
        std::replace(label.begin(), label.end(), '-', '_');
        seconds(benchmark::RegisterBenchmark(("BM_RelaxBuiltin/" + label).c_str(),
                                             [name](benchmark::State& s) { relax(s, knit::builtinChart(name)); }));
    }
    for (const auto& lace : kLaceCharts) {
        const std::string text = lace[1], label = lace[0];
        seconds(benchmark::RegisterBenchmark(("BM_RelaxLace/" + label).c_str(), [text, label](benchmark::State& s) {
            relax(s, knit::parseChart(text, label));
        }));
    }
    for (const auto& carried : kCarriedCharts) {
        const std::string text = carried[1], label = carried[0];
        seconds(benchmark::RegisterBenchmark(
            ("BM_RelaxIntarsiaCarried/" + label).c_str(),
            [text, label](benchmark::State& s) { relaxCountingCrossings(s, knit::parseChart(text, label)); }));
    }
    // RelaxOptions::affinePeriod (faster, for previews; off by default).
    for (const char* name : {"chart:eyelet-mesh", "chart:intarsia-blocks"}) {
        std::string label = std::string(name).substr(6);
        std::replace(label.begin(), label.end(), '-', '_');
        seconds(benchmark::RegisterBenchmark(("BM_RelaxAffineBuiltin/" + label).c_str(), [name](benchmark::State& s) {
            relax(s, knit::builtinChart(name), true);
        }));
    }
    benchmark::RegisterBenchmark("BM_RelaxStockinette2x2", [](benchmark::State& s) {
        relax(s, knit::builtinChart("chart:stockinette"));
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_RelaxAffineStockinette2x2", [](benchmark::State& s) {
        relax(s, knit::builtinChart("chart:stockinette"), true);
    })->Unit(benchmark::kMillisecond);
    seconds(benchmark::RegisterBenchmark(
        "BM_RelaxCable12x16", [](benchmark::State& s) { relax(s, knit::parseChart(cableCell(), "cable12x16")); }));
    seconds(benchmark::RegisterBenchmark("BM_RelaxAffineCable12x16", [](benchmark::State& s) {
        relax(s, knit::parseChart(cableCell(), "cable12x16"), true);
    }));
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
