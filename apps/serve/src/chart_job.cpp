// Parsing and relaxing the page's chart (chart_job.hpp).
#include "chart_job.hpp"

#include <iterator>
#include <regex>

#include <tbb/task_arena.h>

#include "jobs.hpp"
#include "knit/chart_warnings.hpp"
#include "knit/error.hpp"

namespace knit::serve {

ChartTextError::ChartTextError(int line, int column, const std::string& message)
    : std::runtime_error(std::to_string(line) + ":" + std::to_string(column) + ": " + message),
      line_(line),
      column_(column),
      message_(message) {}

nlohmann::json ChartTextError::json() const {
    return {{"error", what()}, {"line", line_}, {"column", column_}, {"message", message_}};
}

Chart parsePageChart(const std::string& text, int maxStitches) {
    Chart chart;
    try {
        chart = parseChart(text, "chart");
    } catch (const Error& e) {
        // "chart:LINE:COLUMN: what" (knit/chart.hpp), or "chart: what" without a position.
        static const std::regex positioned(R"(^chart:(\d+):(\d+): ([\s\S]*)$)");
        std::smatch m;
        const std::string what = e.what();
        if (std::regex_match(what, m, positioned)) throw ChartTextError(std::stoi(m[1]), std::stoi(m[2]), m[3]);
        const std::string prefix = "chart: ";
        throw ChartTextError(1, 1, what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
    }
    if (int64_t(chart.width) * chart.height > maxStitches)
        throw ChartTextError(1, 1,
                             "the chart has " + std::to_string(chart.width) + " x " + std::to_string(chart.height) +
                                 " stitches, over the page's limit of " + std::to_string(maxStitches));
    return chart;
}

namespace {

template <class T>
void appendBytes(std::string& key, const T* data, size_t count) {
    key.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

}  // namespace

std::string relaxationKey(const ChartCell& cell, const ChartPatternOptions& options) {
    const Pattern& p = cell.pattern;
    std::string key;
    key.reserve(64 + p.points.size() * (sizeof(glm::dvec3) + sizeof(PeriodicEdge) + sizeof(double)));
    const double numbers[] = {options.radius,
                              double(options.samplesPerStitch),
                              options.restLength,
                              double(options.maxIterations),
                              double(options.affinePeriod),
                              double(options.hessianPreconditioner),
                              options.contact,
                              options.relativeEnergyTolerance,
                              double(options.energyWindow),
                              p.px,
                              p.py,
                              p.radius};
    appendBytes(key, numbers, std::size(numbers));
    const uint64_t counts[] = {p.points.size(), p.edges.size(), cell.restScale.size()};
    appendBytes(key, counts, std::size(counts));
    appendBytes(key, p.points.data(), p.points.size());
    for (const PeriodicEdge& e : p.edges) {
        const int32_t edge[] = {int32_t(e.v0), int32_t(e.v1), int32_t(e.dx), int32_t(e.dy)};
        appendBytes(key, edge, std::size(edge));
    }
    appendBytes(key, cell.restScale.data(), cell.restScale.size());
    return key;
}

bool RelaxedCharts::find(const std::string& key, CellRelaxation& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (it->first != key) continue;
        entries_.splice(entries_.begin(), entries_, it);
        out = entries_.front().second;
        return true;
    }
    return false;
}

void RelaxedCharts::put(const std::string& key, const CellRelaxation& relaxation) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.emplace_front(key, relaxation);
    while (entries_.size() > capacity_) entries_.pop_back();
}

void addDesignWarnings(const Chart& chart, const ChartCell& cell, nlohmann::json& warnings) {
    // The library's warnings (long floats, rows stacked), as `knit chart` and Python say them.
    constexpr int kMaxFloat = 5;
    for (const ChartWarning& w : chartWarnings(chart, cell, kMaxFloat))
        warnings.push_back(w.line > 0 ? "line " + std::to_string(w.line) + ", " + w.text : w.text);
    int eyelets = 0;
    for (StitchOp op : chart.op) eyelets += op == StitchOp::YarnOver ? 1 : 0;
    if (eyelets > 0)
        warnings.push_back(std::to_string(eyelets) +
                           (eyelets == 1 ? " yarn-over opens an eyelet" : " yarn-overs open eyelets") +
                           " (holes) per repeat");
}

double previewContactScale() {
    const double coarser = double(ChartPatternOptions{}.samplesPerStitch) / kPreviewSamples;
    return coarser * coarser;
}

ChartPatternOptions previewOptions() {
    ChartPatternOptions o;
    o.samplesPerStitch = kPreviewSamples;
    o.hessianPreconditioner = kPreviewPreconditioner;
    o.contact *= previewContactScale();
    o.energyWindow = kPreviewEnergyWindow;
    o.relativeEnergyTolerance = kPreviewRelativeEnergyTolerance;
    return o;
}

ChartCellOptions cellOptions(const ChartPatternOptions& options) {
    ChartCellOptions o;
    o.radius = options.radius;
    o.samplesPerStitch = options.samplesPerStitch;
    return o;
}

CellRelaxation relaxPageCell(const Chart& chart, const ChartPatternOptions& options) {
    ChartPattern relaxed;
    tbb::task_arena oneCore(1);
    oneCore.execute([&] { relaxed = relaxChart(chart, options); });
    if (relaxed.relaxed.stopped) throw JobCancelled();
    CellRelaxation out;
    out.points = std::move(relaxed.relaxed.pattern.points);
    out.px = relaxed.relaxed.pattern.px;
    out.py = relaxed.relaxed.pattern.py;
    out.iterations = relaxed.relaxed.iterations;
    out.converged = relaxed.relaxed.converged;
    out.seconds = relaxed.seconds;
    out.minDistance = relaxed.relaxed.minDistance;
    out.samplesPerStitch = options.samplesPerStitch;
    return out;
}

RelaxedChart relaxedChart(const Chart& chart, const ChartCell& cell, const CellRelaxation& r) {
    if (r.points.size() != cell.pattern.points.size())
        throw std::logic_error("a cell relaxation used for another cell");
    RelaxedChart out;
    // As relaxYarn returns it: the initial cell with the relaxed points and period, twist 0.
    out.pattern = cell.pattern;
    out.pattern.points = r.points;
    out.pattern.px = r.px;
    out.pattern.py = r.py;
    out.pattern.twist.assign(r.points.size(), 0.0);
    out.pattern.extraBlocks.clear();
    out.stats = {{"iterations", r.iterations},
                 {"converged", r.converged},
                 {"seconds", r.seconds},
                 {"min_distance", r.minDistance},
                 {"width", chart.width},
                 {"height", chart.height},
                 {"samples_per_stitch", r.samplesPerStitch}};
    addDesignWarnings(chart, cell, out.warnings);
    if (!r.converged)
        out.warnings.push_back("the relaxation stopped at its iteration cap (" + std::to_string(r.iterations) +
                               "): the stitches may not be at rest yet");
    // Yarns pressed into each other (the contact settles just inside 2.05 radii; the tests of
    // every built-in chart stay above 1.9).
    if (r.minDistance < 1.9)
        out.warnings.push_back("yarns press into each other (closest centrelines " +
                               std::to_string(r.minDistance).substr(0, 4) +
                               " yarn radii apart, under 1.9): the fabric is packed too tight here");
    return out;
}

}  // namespace knit::serve
