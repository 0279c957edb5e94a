// A stitch chart to a relaxed periodic pattern: the initial cell, then the relaxation.
#include "knit/chart_pattern.hpp"

#include <chrono>

namespace knit {

ChartPattern relaxChart(const Chart& chart, const ChartPatternOptions& options) {
    ChartPattern out;
    // Step 1: the initial cell with the crossing structure of the chart.
    ChartCellOptions cellOptions;
    cellOptions.radius = options.radius;
    cellOptions.samplesPerStitch = options.samplesPerStitch;
    out.cell = chartToCell(chart, cellOptions);
    // Step 2: the yarn comes to rest with the period free.
    RelaxOptions relax;
    relax.restLength = options.restLength;
    relax.restScale = out.cell.restScale;
    relax.maxIterations = options.maxIterations;
    relax.affinePeriod = options.affinePeriod;
    relax.onStep = options.onStep;
    relax.stepInterval = options.stepInterval;
    const auto start = std::chrono::steady_clock::now();
    out.relaxed = relaxYarn(out.cell.pattern, relax);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace knit
