// knit serve's relaxations (issue 27: relaxed yarns of every chart up to 4 x 4 within 0.5 s of
// the last keystroke). For the twelve charts of tests/serve/page_test.mjs (a cable and lace
// among them), then the built-in charts up to 4 x 4, each relaxed by relaxChart on one core as
// the server runs it (relaxPageCell): `preview`, what the page shows first (previewOptions: 10
// samples per stitch, plain L-BFGS, the contact weight times (24 / 10)^2, the shorter energy
// stop window), `preview_default_stop` (the same with RelaxOptions' energy stop test, as before),
// `preview_preconditioned` (with the Hessian preconditioner) and `full` (24 samples per stitch,
// as `knit chart`). Counters: the process CPU seconds of one relaxation (the machine may be
// shared), iterations, converged, the smallest yarn distance, the energy and L r / A (which rest
// state it reached). BM_PreviewToFull: the page test's twelve charts, the preview against the full
// relaxation (to_full_max_r, to_full_rms_r: bench/cell_distance.hpp; the period's ratios).
// docs/serve.md has the numbers. Run: build/bench/serve_bench
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "bench_clock.hpp"
#include "cell_distance.hpp"
#include "chart_job.hpp"
#include "knit/chart_pattern.hpp"
#include "pattern_measures.hpp"
#include "knit/chart.hpp"

namespace {

// The page test's charts (in its order), then typed charts (a cable, a lace row) and the built-ins
// up to 4 x 4: {label, text}.
using NamedChart = std::pair<std::string, std::string>;
std::vector<NamedChart> chartTexts() {
    std::vector<NamedChart> charts;
    for (const char* text :
         {"k p\nk p", "k k p p\nk k p p\np p k k\np p k k", "k p k\np k p\nk p k", "k p\np k",
          "k k p p\np k k p\np p k k\nk p p k", "k k k\np p p\nk p k", "k p p\np k p\np p k", "k k p p\nk k p p",
          "k p k p\np k p k\nk k p p\np p k k", "c2/2f\nk k k k\nk k k k\nk k k k", "k yo k2tog k\nk k k k",
          "k k k k\nk k k2tog yo\nk k k k\nk2tog yo k k"}) {
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

// The benchmark's loop: relaxChart with `options` on one core, as relaxPageCell does; `cpu` is the
// process CPU seconds of the last run.
knit::ChartPattern relaxOnOneCore(benchmark::State& state, const knit::Chart& chart,
                                  const knit::ChartPatternOptions& options, double& cpu) {
    knit::ChartPattern r;
    for (auto _ : state) {
        const double start = knit::bench::cpuSeconds();
        tbb::task_arena oneCore(1);
        oneCore.execute([&] { r = knit::relaxChart(chart, options); });
        cpu = knit::bench::cpuSeconds() - start;
    }
    return r;
}

// Runs relaxChart with `options` on chart N (state.range(0)) on one core, as relaxPageCell does,
// and reports its CPU time and how it went.
void BM_Relax(benchmark::State& state, const knit::ChartPatternOptions& options) {
    const auto& [label, text] = charts()[size_t(state.range(0))];
    const knit::Chart chart = knit::parseChart(text, "chart");
    double cpu = 0;
    const knit::ChartPattern r = relaxOnOneCore(state, chart, options, cpu);
    state.counters["cpu_s"] = cpu;
    state.counters["iterations"] = r.relaxed.iterations;
    state.counters["converged"] = r.relaxed.converged;
    state.counters["min_distance_r"] = r.relaxed.minDistance;
    state.counters["energy"] = r.relaxed.energy;
    state.counters["L_r_per_A"] = knit::bench::lengthPerArea(r.relaxed.pattern);
    state.SetLabel(std::to_string(chart.width) + "x" + std::to_string(chart.height) + " " + label);
}

// The full relaxation of chart N (as `knit chart`), relaxed once per run.
const knit::Pattern& fullRelaxation(size_t n) {
    static std::vector<knit::Pattern> done(charts().size());
    if (done[n].points.empty())
        done[n] = knit::relaxChart(knit::parseChart(charts()[n].second, "chart")).relaxed.pattern;
    return done[n];
}

// The preview of chart N (state.range(0)) with `options`, as BM_Relax, and how far its yarns lie
// from the full relaxation's (cellDistance, in yarn radii; the full relaxation is not timed).
void BM_PreviewToFull(benchmark::State& state, const knit::ChartPatternOptions& options) {
    const size_t n = size_t(state.range(0));
    const knit::Chart chart = knit::parseChart(charts()[n].second, "chart");
    const knit::Pattern& full = fullRelaxation(n);
    double cpu = 0;
    const knit::ChartPattern r = relaxOnOneCore(state, chart, options, cpu);
    const knit::bench::CellDistance d = knit::bench::cellDistance(r.relaxed.pattern, full);
    state.counters["cpu_s"] = cpu;
    state.counters["iterations"] = r.relaxed.iterations;
    state.counters["min_distance_r"] = r.relaxed.minDistance;
    state.counters["to_full_max_r"] = d.max;
    state.counters["to_full_rms_r"] = d.rms;
    state.counters["px_over_full"] = r.relaxed.pattern.px / full.px;
    state.counters["py_over_full"] = r.relaxed.pattern.py / full.py;
    state.SetLabel(charts()[n].first);
}

// The preview with RelaxOptions' default energy stop test (a window of 500 iterations, 1e-6), as
// before the preview stopped sooner.
knit::ChartPatternOptions previewWithDefaultStop() {
    knit::ChartPatternOptions o = knit::serve::previewOptions();
    o.energyWindow = knit::RelaxOptions{}.energyWindow;
    o.relativeEnergyTolerance = knit::RelaxOptions{}.relativeEnergyTolerance;
    return o;
}

knit::ChartPatternOptions preconditionedPreview() {
    knit::ChartPatternOptions o = knit::serve::previewOptions();
    o.hessianPreconditioner = true;
    return o;
}

void allCharts(benchmark::internal::Benchmark* b) {
    b->DenseRange(0, int(charts().size()) - 1)->Unit(benchmark::kMillisecond)->Iterations(1);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Relax, preview, knit::serve::previewOptions())->Apply(allCharts);
BENCHMARK_CAPTURE(BM_Relax, preview_default_stop, previewWithDefaultStop())->Apply(allCharts);
BENCHMARK_CAPTURE(BM_Relax, preview_preconditioned, preconditionedPreview())->Apply(allCharts);
BENCHMARK_CAPTURE(BM_Relax, full, knit::ChartPatternOptions{})->Apply(allCharts);
BENCHMARK_CAPTURE(BM_PreviewToFull, preview, knit::serve::previewOptions())
    ->DenseRange(0, 11)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_PreviewToFull, preview_default_stop, previewWithDefaultStop())
    ->DenseRange(0, 11)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_MAIN();
