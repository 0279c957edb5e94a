// chart_job.hpp — a chart from the page: parsed (errors at their line and column), relaxed once
// (kept in memory by its cell's geometry), and its relaxation's warnings.
#pragma once
#include <functional>
#include <list>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include <nlohmann/json.hpp>

#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/chart_topology.hpp"
#include "knit/pattern.hpp"

namespace knit::serve {

// A chart the parser refused: shown by the page as `LINE:COLUMN: message`, as `knit chart`
// prints it (without the file name).
class ChartTextError : public std::runtime_error {
public:
    ChartTextError(int line, int column, const std::string& message);
    int line() const { return line_; }
    int column() const { return column_; }
    const std::string& message() const { return message_; }
    nlohmann::json json() const;  // {"error": "L:C: message", "line", "column", "message"}

private:
    int line_, column_;
    std::string message_;
};

// Parses the page's chart text; throws ChartTextError (line 0, column 0 when the parser names no
// position, e.g. an empty chart).
Chart parsePageChart(const std::string& text, int maxStitches);

// A relaxed chart and what the page warns about.
struct RelaxedChart {
    Pattern pattern;
    nlohmann::json warnings = nlohmann::json::array();  // strings
    // iterations, converged, seconds, min_distance, width, height, samples_per_stitch
    nlohmann::json stats;
};

// What the relaxation of a chart's cell gave: the relaxed points and period, and how it went.
// It depends only on the cell's geometry and rest scales and the options (relaxationKey), not
// on the chart's text: comments, spacing and, outside stranded colourwork, the colours do not
// change it.
struct CellRelaxation {
    std::vector<glm::dvec3> points;
    double px = 0, py = 0;
    int iterations = 0;
    bool converged = false;
    double seconds = 0, minDistance = 0;
    int samplesPerStitch = 0;
};

// The key of a cell's relaxation: the relaxation options and the initial cell's period, radius,
// points, edges and rest scales, byte for byte.
std::string relaxationKey(const ChartCell& cell, const ChartPatternOptions& options);

// The last few cell relaxations by key (a page toggling between two charts, or changing only
// colours or comments, relaxes each cell once).
class RelaxedCharts {
public:
    explicit RelaxedCharts(size_t capacity = 32) : capacity_(capacity) {}
    bool find(const std::string& key, CellRelaxation& out);
    void put(const std::string& key, const CellRelaxation& relaxation);

private:
    size_t capacity_;
    std::mutex mutex_;
    std::list<std::pair<std::string, CellRelaxation>> entries_;  // most recent first
};

// What a designer is warned about in the chart itself, appended to `warnings` (strings): floats
// longer than the common rule of 5 stitches (they snag; `knit chart --max-float`), and the eyelets
// its yarn-overs open. `cell` is the chart's cell (chartToCell), relaxed or not.
void addDesignWarnings(const Chart& chart, const ChartCell& cell, nlohmann::json& warnings);

// Samples per stitch of the swatch's preview: the cell relaxed at 10 instead of `knit chart`'s 24
// converges several times sooner, so the page shows relaxed yarns while the full relaxation runs
// (build/bench/serve_bench, docs/serve.md "Measured": the charts up to 4 x 4 in 8-245 ms of CPU
// by plain L-BFGS with its contact weight, at load 13-15, against 0.07-3.8 s for the full
// relaxation). At 12 it took up to twice as long
// (eyelet-mesh 3232 iterations); at 8 the 3 x 3 moss did not converge.
constexpr int kPreviewSamples = 10;
// The preview relaxes by plain L-BFGS (ChartPatternOptions::hessianPreconditioner false): at 10
// samples per stitch the preconditioner's factorisations cost more CPU than the iterations they
// save, and every preview settles in the same rest state either way (docs/serve.md).
constexpr bool kPreviewPreconditioner = false;

// The preview's contact weight, over `knit chart`'s: RelaxOptions::contact is per pair of
// segments, and two yarns touching along a stretch have about (samples per stitch)^2 pairs of
// segments there, so at 10 samples per stitch and the same weight the preview's yarns pressed
// into each other (closest centrelines 1.60-2.03 radii, 17 of 24 cells under 1.9, against
// 1.97-2.05 in the full relaxation). Weighted by (24 / 10)^2 they keep 1.96-2.05 radii apart, for
// 1.9 times the iterations and 1.6 times the CPU (build/bench/serve_bench, docs/serve.md).
double previewContactScale();

// The preview's energy stop test (ChartPatternOptions::energyWindow, relativeEnergyTolerance):
// it stops when the energy fell by at most 1e-5 of its whole decrease over the last 200
// iterations, instead of `knit chart`'s 1e-6 over 500. Over the page test's twelve charts this
// took a third fewer iterations (13 276 against 19 836) and moved the preview's yarns by at most
// 0.79 radii (RMS 0.21), against the 0.56-3.45 radii they lie from the full relaxation either
// way (build/bench/serve_bench, BM_PreviewToFull; docs/serve.md).
constexpr int kPreviewEnergyWindow = 200;
constexpr double kPreviewRelativeEnergyTolerance = 1e-5;

// The options of the page's preview.
ChartPatternOptions previewOptions();

// The initial cell relaxChart builds with `options`.
ChartCellOptions cellOptions(const ChartPatternOptions& options);

// Relaxes `chart` as relaxChart does with `options` (onStep as in ChartPatternOptions: return
// false to stop, then JobCancelled), on the calling thread only: a job is one core (on this
// 2-core machine the relaxation of a 4 x 4 chart took 0.67 s on one thread and 0.86 s on two,
// docs/serve.md).
CellRelaxation relaxPageCell(const Chart& chart, const ChartPatternOptions& options);

// The chart relaxed: `cell` (chartToCell of `chart`) with the points and period of its
// `relaxation`, exactly the pattern relaxChart would give, and the page's warnings.
RelaxedChart relaxedChart(const Chart& chart, const ChartCell& cell, const CellRelaxation& relaxation);

}  // namespace knit::serve
