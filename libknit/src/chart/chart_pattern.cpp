// A stitch chart to a relaxed periodic pattern: the initial cell, then the relaxation.
#include "knit/chart_pattern.hpp"

#include <chrono>
#include <string>

#include "knit/error.hpp"

namespace knit {

namespace {

using Clock = std::chrono::steady_clock;

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

// Step 1: the initial cell with the crossing structure of the chart.
ChartCell initialCell(const Chart& chart, const ChartPatternOptions& options) {
    checkStackedSize(chart, chartStacking(chart), options.samplesPerStitch, kMaxRelaxedChartVertices,
                     "about 2000 stitches; the relaxation would run for many minutes");
    ChartCellOptions cellOptions;
    cellOptions.radius = options.radius;
    cellOptions.samplesPerStitch = options.samplesPerStitch;
    ChartCell cell = chartToCell(chart, cellOptions);
    checkRelaxCost(chart, cell, options.samplesPerStitch);
    return cell;
}

// Step 2: the yarn comes to rest with the period free.
RelaxResult relaxCell(const ChartCell& cell, const ChartPatternOptions& options) {
    RelaxOptions relax;
    relax.restLength = options.restLength;
    relax.restScale = cell.restScale;
    relax.anchors = cell.anchors;
    relax.maxIterations = options.maxIterations;
    relax.affinePeriod = options.affinePeriod;
    relax.hessianPreconditioner = options.hessianPreconditioner;
    relax.contact = options.contact;
    relax.relativeEnergyTolerance = options.relativeEnergyTolerance;
    relax.energyWindow = options.energyWindow;
    relax.onStep = options.onStep;
    relax.stepInterval = options.stepInterval;
    return relaxYarn(cell.pattern, relax);
}

}  // namespace

ChartPattern relaxChart(const Chart& chart, const ChartPatternOptions& options) {
    ChartPattern out;
    const auto begin = Clock::now();
    out.cell = initialCell(chart, options);
    out.relaxed = relaxCell(out.cell, options);
    out.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return out;
}

}  // namespace knit
