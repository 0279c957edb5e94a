// knit serve's relaxations (issue 27: converged yarns of every chart up to 4 x 4 within 0.5 s of
// the last keystroke). For the charts of tests/serve/page_test.mjs, the built-in charts up to
// 4 x 4 and a few typed ones (a cable, a lace row), each relaxed by relaxChart on one core as the
// server runs it (relaxPageCell): `preview`, what the page shows first (previewOptions: 10
// samples per stitch, plain L-BFGS, the contact weight times (24 / 10)^2),
// `preview_preconditioned` (the same with the Hessian preconditioner) and `full` (24 samples
// per stitch, as `knit chart`). Counters: the process CPU seconds of one relaxation (the machine may be shared),
// iterations, converged, the smallest yarn distance, the energy and L r / A (which rest state it
// reached). docs/serve.md has the numbers. Run: build/bench/serve_bench
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "bench_clock.hpp"
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

// Runs relaxChart with `options` on chart N (state.range(0)) on one core, as relaxPageCell does,
// and reports its CPU time and how it went.
void BM_Relax(benchmark::State& state, const knit::ChartPatternOptions& options) {
    const auto& [label, text] = charts()[size_t(state.range(0))];
    const knit::Chart chart = knit::parseChart(text, "chart");
    knit::ChartPattern r;
    double cpu = 0;
    for (auto _ : state) {
        const double start = knit::bench::cpuSeconds();
        tbb::task_arena oneCore(1);
        oneCore.execute([&] { r = knit::relaxChart(chart, options); });
        cpu = knit::bench::cpuSeconds() - start;
    }
    state.counters["cpu_s"] = cpu;
    state.counters["iterations"] = r.relaxed.iterations;
    state.counters["converged"] = r.relaxed.converged;
    state.counters["min_distance_r"] = r.relaxed.minDistance;
    state.counters["energy"] = r.relaxed.energy;
    state.counters["L_r_per_A"] = knit::bench::lengthPerArea(r.relaxed.pattern);
    state.SetLabel(std::to_string(chart.width) + "x" + std::to_string(chart.height) + " " + label);
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
BENCHMARK_CAPTURE(BM_Relax, preview_preconditioned, preconditionedPreview())->Apply(allCharts);
BENCHMARK_CAPTURE(BM_Relax, full, knit::ChartPatternOptions{})->Apply(allCharts);
BENCHMARK_MAIN();
