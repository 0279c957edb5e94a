// knit serve's relaxations (issue 27: relaxed yarns of a chart up to 4 x 4 within 0.5 s of the last
// keystroke). For the charts of tests/serve/page_test.mjs, the page's preview (kPreviewSamples
// samples per stitch) and the full relaxation (24, as `knit chart`), each on one core as the server
// runs them (relaxPageCell). The CPU column is the relaxation's CPU time; docs/serve.md has the
// numbers. Run: build/bench/serve_bench
#include <benchmark/benchmark.h>

#include "chart_job.hpp"

namespace {

// The page test's charts, in its order.
const char* const kCharts[] = {"k p\nk p",
                               "k k p p\nk k p p\np p k k\np p k k",
                               "k p k\np k p\nk p k",
                               "k p\np k",
                               "k k p p\np k k p\np p k k\nk p p k",
                               "k k k\np p p\nk p k",
                               "k p p\np k p\np p k",
                               "k k p p\nk k p p",
                               "k p k p\np k p k\nk k p p\np p k k"};

void BM_Relax(benchmark::State& state, int samplesPerStitch) {
    const std::string text = kCharts[state.range(0)];
    const knit::Chart chart = knit::parseChart(text, "chart");
    knit::ChartPatternOptions options;
    options.samplesPerStitch = samplesPerStitch;
    knit::serve::CellRelaxation r;
    for (auto _ : state) r = knit::serve::relaxPageCell(chart, options);
    state.counters["iterations"] = r.iterations;
    state.counters["converged"] = r.converged;
    state.counters["min_distance_r"] = r.minDistance;
    std::string label = text;
    for (char& c : label) c = c == '\n' ? '/' : c;
    state.SetLabel(std::to_string(chart.width) + "x" + std::to_string(chart.height) + " " + label);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Relax, preview, knit::serve::kPreviewSamples)
    ->DenseRange(0, 8)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Relax, full, knit::ChartPatternOptions{}.samplesPerStitch)
    ->DenseRange(0, 8)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_MAIN();
