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
    // RelaxOptions::contact, the contact penalty's weight. It is per pair of segments, not per
    // length of yarn: a cell sampled coarser has fewer pairs along each contact, so at the same
    // weight its yarns press deeper into each other (knit serve's preview at 10 samples per
    // stitch raises it, docs/serve.md). At its default it adds nothing to the cache key.
    double contact = RelaxOptions{}.contact;
    // RelaxOptions' energy stop test: the relaxation stops when the energy fell by at most
    // relativeEnergyTolerance x (its whole decrease so far) over the last energyWindow
    // iterations. knit serve's preview stops sooner (docs/serve.md); at their defaults they add
    // nothing to the cache key.
    double relativeEnergyTolerance = RelaxOptions{}.relativeEnergyTolerance;
    int energyWindow = RelaxOptions{}.energyWindow;
    // Progress and cancellation of the relaxation (RelaxOptions::onStep); not part of the
    // cache key, since it does not change the result.
    RelaxStepFn onStep;
    int stepInterval = 50;
};

struct ChartPattern {
    ChartCell cell;       // the initial cell and its stitch record (vertex ranges stay valid)
    RelaxResult relaxed;  // relaxed.pattern is the result
    double seconds = 0;   // relaxation wall time
};

// The relaxation's cost grows with the cell's yarn vertices (stitches x samples per stitch):
// about 0.14 s per stitch at 24 samples on one loaded core (docs/charts.md, "Size limit"). A
// cell with more vertices than this is refused before relaxing: 2000 stitches at 24 samples.
constexpr size_t kMaxRelaxedChartVertices = 48000;

// Throws knit::Error for bad options (radius, samples), an invalid chart cell or one of more
// than kMaxRelaxedChartVertices vertices (before relaxing it).
ChartPattern relaxChart(const Chart& chart, const ChartPatternOptions& options = {});

}  // namespace knit
