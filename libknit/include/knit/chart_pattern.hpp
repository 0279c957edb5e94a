// knit/chart_pattern.hpp — a stitch chart all the way to a relaxed periodic pattern:
// parse (knit/chart.hpp) -> initial cell (knit/chart_topology.hpp) -> relaxYarn (knit/relax.hpp).
#pragma once
#include <string>

#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"

namespace knit {

struct ChartPatternOptions {
    double radius = 0.001;  // yarn radius (metres)
    int samplesPerStitch = 24;
    // The initial cell is a loose construction: the yarn's rest length is this fraction of it,
    // so relaxation pulls the stitches tight until the yarns touch (0.8 gives the HYLC
    // stockinette's yarn length per area within 7%, see docs/charts.md).
    double restLength = 0.8;
    int maxIterations = 4000;
    bool affinePeriod = false;          // RelaxOptions::affinePeriod: faster, for previews (part of the cache key)
    bool hessianPreconditioner = true;  // RelaxOptions::hessianPreconditioner of this relaxation
    // Warm start (off by default): the chart is first relaxed at warmStartSamples samples per
    // stitch (the coarse stage, warmStartOptions), and the relaxation at samplesPerStitch starts
    // from that rest state carried to its vertices, without RelaxOptions::plainIterations (the
    // rest state is chosen). 0, or not below samplesPerStitch: from the initial cell. Measured at
    // 10 (docs/serve.md, "Warm start"): faster on some charts, slower on others, and it ends in
    // other rest states (the relaxation has several; the energies are listed there).
    int warmStartSamples = 0;
    bool warmStartPreconditioner = false;  // the coarse stage's hessianPreconditioner
    // Progress and cancellation of the relaxation (RelaxOptions::onStep); not part of the
    // cache key, since it does not change the result.
    RelaxStepFn onStep;
    int stepInterval = 50;
};

struct ChartPattern {
    ChartCell cell;       // the initial cell and its stitch record (vertex ranges stay valid)
    RelaxResult relaxed;  // relaxed.pattern is the result
    double seconds = 0;   // relaxation wall time (the coarse stage's included)
    // The coarse stage's iterations when the relaxation was warm-started from it, else 0.
    int warmStartIterations = 0;
};

// The relaxation's cost grows with the cell's yarn vertices (stitches x samples per stitch):
// about 0.14 s per stitch at 24 samples on one loaded core (docs/charts.md, "Size limit"). A
// cell with more vertices than this is refused before relaxing: 2000 stitches at 24 samples.
constexpr size_t kMaxRelaxedChartVertices = 48000;

// Throws knit::Error for bad options (radius, samples), an invalid chart cell or one of more
// than kMaxRelaxedChartVertices vertices (before relaxing it). With a warm start
// (ChartPatternOptions::warmStartSamples) onStep is called by both stages (the coarse one's
// RelaxStep::pattern has the coarse cell's vertices); stopped in the coarse stage, the result's
// relaxed.stopped is set and relaxed.pattern is the initial cell.
ChartPattern relaxChart(const Chart& chart, const ChartPatternOptions& options = {});

// The options of relaxChart's coarse stage for `options`: warmStartSamples samples per stitch,
// warmStartPreconditioner, no warm start of its own.
ChartPatternOptions warmStartOptions(const ChartPatternOptions& options);

}  // namespace knit
