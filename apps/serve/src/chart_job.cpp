// Parsing and relaxing the page's chart (chart_job.hpp).
#include "chart_job.hpp"

#include <regex>

#include "jobs.hpp"
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

bool RelaxedCharts::find(const std::string& text, RelaxedChart& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (it->first != text) continue;
        entries_.splice(entries_.begin(), entries_, it);
        out = entries_.front().second;
        return true;
    }
    return false;
}

void RelaxedCharts::put(const std::string& text, const RelaxedChart& relaxed) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.emplace_front(text, relaxed);
    while (entries_.size() > capacity_) entries_.pop_back();
}

void addDesignWarnings(const Chart& chart, const ChartCell& cell, nlohmann::json& warnings) {
    constexpr int kMaxFloat = 5;
    for (const ChartFloat& f : cell.floats) {
        if (f.columns <= kMaxFloat) continue;
        const int last = (f.firstColumn + f.columns - 1) % chart.width + 1;
        warnings.push_back("line " + std::to_string(chart.rowLine[size_t(f.row)]) + ", row " +
                           std::to_string(f.row + 1) + ": a float over columns " + std::to_string(f.firstColumn + 1) +
                           "-" + std::to_string(last) + " is " + std::to_string(f.columns) +
                           " stitches long, longer than " + std::to_string(kMaxFloat) +
                           " (long floats snag: catch it or shorten the run)");
    }
    int eyelets = 0;
    for (StitchOp op : chart.op) eyelets += op == StitchOp::YarnOver ? 1 : 0;
    if (eyelets > 0)
        warnings.push_back(std::to_string(eyelets) +
                           (eyelets == 1 ? " yarn-over opens an eyelet" : " yarn-overs open eyelets") +
                           " (holes) per repeat");
}

RelaxedChart relaxPageChart(const Chart& chart, const RelaxStepFn& onStep) {
    ChartPatternOptions options;
    options.onStep = onStep;
    options.stepInterval = 20;
    const ChartPattern relaxed = relaxChart(chart, options);
    if (relaxed.relaxed.stopped) throw JobCancelled();
    RelaxedChart out;
    out.pattern = relaxed.relaxed.pattern;
    out.stats = {{"iterations", relaxed.relaxed.iterations},
                 {"converged", relaxed.relaxed.converged},
                 {"seconds", relaxed.seconds},
                 {"min_distance", relaxed.relaxed.minDistance},
                 {"width", chart.width},
                 {"height", chart.height}};
    addDesignWarnings(chart, relaxed.cell, out.warnings);
    if (!relaxed.relaxed.converged)
        out.warnings.push_back("the relaxation stopped at its iteration cap (" +
                               std::to_string(relaxed.relaxed.iterations) + "): the stitches may not be at rest yet");
    // Yarns pressed into each other (the contact settles just inside 2.05 radii; the tests of
    // every built-in chart stay above 1.9).
    if (relaxed.relaxed.minDistance < 1.9)
        out.warnings.push_back("yarns press into each other (closest centrelines " +
                               std::to_string(relaxed.relaxed.minDistance).substr(0, 4) +
                               " yarn radii apart, under 1.9): the fabric is packed too tight here");
    return out;
}

}  // namespace knit::serve
