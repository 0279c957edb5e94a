// A stitch chart to a relaxed periodic pattern: the initial cell, then the relaxation, warm-started
// from the chart relaxed at fewer samples per stitch (chart_warm_start.hpp).
#include "knit/chart_pattern.hpp"

#include <chrono>
#include <optional>
#include <string>

#include "chart_warm_start.hpp"
#include "knit/error.hpp"

namespace knit {

namespace {

using Clock = std::chrono::steady_clock;

// The warm start is kept only when the two samplings follow one curve to within this (in yarn
// radii, half a stitch's width): at 10 and 24 samples per stitch the built-ins differ by 1.1-3.2 r
// (the coarse chords cut the loops' curves short; ChartWarmStart.theCoarseCellCarriesToTheFineOne
// prints it). Beyond it the relaxation starts from the initial cell.
constexpr double kMaxStartMismatch = 4.0;

// Refuses a cell whose relaxation would run for many minutes, before it starts.
void checkRelaxCost(const Chart& chart, const ChartCell& cell, int samplesPerStitch) {
    const size_t vertices = cell.pattern.points.size();
    if (vertices <= kMaxRelaxedChartVertices) return;
    throw Error(chart.name + ": " + std::to_string(chart.height) + " rows x " + std::to_string(chart.width) +
                " stitches at " + std::to_string(samplesPerStitch) + " samples per stitch make " +
                std::to_string(vertices) + " yarn vertices to relax, more than " +
                std::to_string(kMaxRelaxedChartVertices) +
                " (about 2000 stitches; the relaxation would run for many minutes): a chart is one repeat of "
                "the fabric, so chart one repeat and tile it over the garment with the repeats");
}

bool warmStarted(const ChartPatternOptions& options) {
    if (options.warmStartSamples != 0 && options.warmStartSamples < 8)
        throw Error("chart relaxation: the warm start's samples per stitch must be 0 (none) or at least 8, not " +
                    std::to_string(options.warmStartSamples));
    return options.warmStartSamples > 0 && options.warmStartSamples < options.samplesPerStitch;
}

// Step 1: the initial cell with the crossing structure of the chart.
ChartCell initialCell(const Chart& chart, const ChartPatternOptions& options) {
    ChartCellOptions cellOptions;
    cellOptions.radius = options.radius;
    cellOptions.samplesPerStitch = options.samplesPerStitch;
    ChartCell cell = chartToCell(chart, cellOptions);
    checkRelaxCost(chart, cell, options.samplesPerStitch);
    return cell;
}

// Step 2: the yarn comes to rest with the period free, from the initial cell or from `start`.
RelaxResult relaxCell(const ChartCell& cell, const ChartPatternOptions& options, const warmstart::FineStart* start) {
    RelaxOptions relax;
    relax.restLength = options.restLength;
    relax.restScale = cell.restScale;
    relax.anchors = cell.anchors;
    relax.maxIterations = options.maxIterations;
    relax.affinePeriod = options.affinePeriod;
    relax.hessianPreconditioner = options.hessianPreconditioner;
    relax.onStep = options.onStep;
    relax.stepInterval = options.stepInterval;
    if (start) {
        relax.startPoints = start->points;
        relax.startPx = start->px;
        relax.startPy = start->py;
        relax.plainIterations = 0;
    }
    return relaxYarn(cell.pattern, relax);
}

// The relaxation of the chart's cell, warm-started from `coarse` (when given, asked for and
// this chart's cell), else from the initial cell.
ChartPattern relaxFrom(const Chart& chart, const ChartPatternOptions& options, const ChartPattern* coarse) {
    ChartPattern out;
    const auto begin = Clock::now();
    out.cell = initialCell(chart, options);
    std::optional<warmstart::FineStart> start;
    if (coarse && warmStarted(options) && !coarse->relaxed.stopped)
        start = warmstart::carryRelaxed(coarse->cell.pattern, coarse->relaxed.pattern, out.cell.pattern);
    if (start && start->mismatch > kMaxStartMismatch) start.reset();
    out.relaxed = relaxCell(out.cell, options, start ? &*start : nullptr);
    out.warmStartIterations = start ? coarse->relaxed.iterations : 0;
    out.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return out;
}

}  // namespace

ChartPatternOptions warmStartOptions(const ChartPatternOptions& options) {
    ChartPatternOptions coarse = options;
    coarse.samplesPerStitch = options.warmStartSamples;
    coarse.hessianPreconditioner = options.warmStartPreconditioner;
    coarse.warmStartSamples = 0;
    return coarse;
}

ChartPattern relaxChart(const Chart& chart, const ChartPatternOptions& options) {
    if (!warmStarted(options)) return relaxFrom(chart, options, nullptr);
    const auto begin = Clock::now();
    const ChartPattern coarse = relaxFrom(chart, warmStartOptions(options), nullptr);
    ChartPattern out;
    if (coarse.relaxed.stopped) {  // cancelled: nothing more to do
        out.cell = initialCell(chart, options);
        out.relaxed.pattern = out.cell.pattern;
        out.relaxed.stopped = true;
    } else {
        out = relaxFrom(chart, options, &coarse);
    }
    out.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return out;
}

}  // namespace knit
