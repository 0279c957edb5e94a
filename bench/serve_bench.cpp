// knit serve's relaxations (issue 27: converged yarns of every chart up to 4 x 4 within 0.5 s of
// the last keystroke). For the charts of tests/serve/page_test.mjs, the built-in charts up to
// 4 x 4 and a few typed ones (a cable, a lace row), the page's preview (kPreviewSamples samples
// per stitch) and the full relaxation (24, as `knit chart`), each on one core as the server runs
// them (relaxPageCell). Counters: iterations, converged, the smallest yarn distance and the
// process CPU seconds of one relaxation (the machine may be shared); and the preview's cell
// relaxed by plain L-BFGS (BM_RelaxPlain). docs/serve.md has the numbers. Run: build/bench/serve_bench
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "bench_clock.hpp"
#include "chart_job.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"

namespace {

// The page test's charts (in its order), then typed charts (a cable, a lace row) and the built-ins
// up to 4 x 4: {label, text}.
using NamedChart = std::pair<std::string, std::string>;
std::vector<NamedChart> chartTexts() {
    std::vector<NamedChart> charts;
    for (const char* text :
         {"k p\nk p", "k k p p\nk k p p\np p k k\np p k k", "k p k\np k p\nk p k", "k p\np k",
          "k k p p\np k k p\np p k k\nk p p k", "k k k\np p p\nk p k", "k p p\np k p\np p k", "k k p p\nk k p p",
          "k p k p\np k p k\nk k p p\np p k k", "c2/2f\nk k k k\nk k k k\nk k k k", "k yo k2tog k\nk k k k"}) {
        std::string label = text;
        for (char& c : label) c = c == '\n' ? '/' : c;
        charts.emplace_back(label, text);
    }
    for (const std::string& name : knit::builtinChartNames()) {
        const knit::Chart c = knit::builtinChart(name);
        if (c.width <= 4 && c.height <= 4) charts.emplace_back(name, knit::builtinChartText(name));
    }
    return charts;
}

const std::vector<NamedChart>& charts() {
    static const std::vector<NamedChart> all = chartTexts();
    return all;
}

// How one relaxation went.
struct Outcome {
    int iterations = 0;
    bool converged = false;
    double minDistance = 0;
};

// Runs `relax` (of chart N, state.range(0)) and reports its CPU time and Outcome.
template <class Relax>
void measure(benchmark::State& state, const Relax& relax) {
    const auto& [label, text] = charts()[size_t(state.range(0))];
    const knit::Chart chart = knit::parseChart(text, "chart");
    Outcome r;
    double cpu = 0;
    for (auto _ : state) {
        const double start = knit::bench::cpuSeconds();
        r = relax(chart);
        cpu = knit::bench::cpuSeconds() - start;
    }
    state.counters["cpu_s"] = cpu;
    state.counters["iterations"] = r.iterations;
    state.counters["converged"] = r.converged;
    state.counters["min_distance_r"] = r.minDistance;
    state.SetLabel(std::to_string(chart.width) + "x" + std::to_string(chart.height) + " " + label);
}

void BM_Relax(benchmark::State& state, int samplesPerStitch) {
    measure(state, [samplesPerStitch](const knit::Chart& chart) {
        knit::ChartPatternOptions options;
        options.samplesPerStitch = samplesPerStitch;
        const knit::serve::CellRelaxation r = knit::serve::relaxPageCell(chart, options);
        return Outcome{r.iterations, r.converged, r.minDistance};
    });
}

// The preview's cell relaxed as relaxChart does, but by plain L-BFGS
// (RelaxOptions::hessianPreconditioner false), on one core: at 10 samples per stitch the
// preconditioner's factorisations cost more CPU than the iterations they save (docs/serve.md).
void BM_RelaxPlain(benchmark::State& state, int samplesPerStitch) {
    measure(state, [samplesPerStitch](const knit::Chart& chart) {
        knit::ChartCellOptions cellOptions;
        cellOptions.samplesPerStitch = samplesPerStitch;
        const knit::ChartCell cell = knit::chartToCell(chart, cellOptions);
        knit::RelaxOptions options;
        options.restLength = knit::ChartPatternOptions{}.restLength;
        options.restScale = cell.restScale;
        options.anchors = cell.anchors;
        options.hessianPreconditioner = false;
        knit::RelaxResult r;
        tbb::task_arena oneCore(1);
        oneCore.execute([&] { r = knit::relaxYarn(cell.pattern, options); });
        return Outcome{r.iterations, r.converged, r.minDistance};
    });
}

void allCharts(benchmark::internal::Benchmark* b) {
    b->DenseRange(0, int(charts().size()) - 1)->Unit(benchmark::kMillisecond)->Iterations(1);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Relax, preview, knit::serve::kPreviewSamples)->Apply(allCharts);
BENCHMARK_CAPTURE(BM_RelaxPlain, preview_plain, knit::serve::kPreviewSamples)->Apply(allCharts);
BENCHMARK_CAPTURE(BM_Relax, full, knit::ChartPatternOptions{}.samplesPerStitch)->Apply(allCharts);
BENCHMARK_MAIN();
