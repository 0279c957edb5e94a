// chart_job.hpp — a chart from the page: parsed (errors at their line and column), relaxed once
// (kept in memory by text), and its relaxation's warnings.
#pragma once
#include <functional>
#include <list>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

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
    nlohmann::json stats;                               // iterations, converged, seconds, min distance
};

// The last few relaxed charts by text (a page toggling between two charts relaxes each once).
class RelaxedCharts {
public:
    explicit RelaxedCharts(size_t capacity = 32) : capacity_(capacity) {}
    bool find(const std::string& text, RelaxedChart& out);
    void put(const std::string& text, const RelaxedChart& relaxed);

private:
    size_t capacity_;
    std::mutex mutex_;
    std::list<std::pair<std::string, RelaxedChart>> entries_;  // most recent first
};

// What a designer is warned about in the chart itself, appended to `warnings` (strings): floats
// longer than the common rule of 5 stitches (they snag; `knit chart --max-float`), and the eyelets
// its yarn-overs open. `cell` is the chart's cell (chartToCell), relaxed or not.
void addDesignWarnings(const Chart& chart, const ChartCell& cell, nlohmann::json& warnings);

// Relaxes `chart`; `onStep` as in ChartPatternOptions (return false to stop: then JobCancelled).
RelaxedChart relaxPageChart(const Chart& chart, const RelaxStepFn& onStep);

}  // namespace knit::serve
