// A designer's warnings on a chart that builds: long floats and rows stacked (knit/chart_warnings.hpp).
#include "knit/chart_warnings.hpp"

namespace knit {

namespace {

// A float in the knitter's words: its row (1 = the bottom row) and the columns it passes
// (1 = the leftmost; it may wrap round the repeat).
ChartWarning longFloat(const Chart& chart, const ChartFloat& f, int maxFloat) {
    const int first = f.firstColumn + 1;
    const int last = (f.firstColumn + f.columns - 1) % chart.width + 1;
    const std::string colour = f.colour ? std::string(" of colour ") + f.colour : std::string();
    const std::string wraps = last < first ? " (round the repeat)" : "";
    const std::string what = f.carried ? " the yarn" + colour + " carried up from the row below to its moved boundary"
                                       : " the float" + colour;
    const std::string fix = f.carried ? "move the boundary by fewer columns a row" : "shorten the run";
    return {chart.rowLine[size_t(f.row)],
            "row " + std::to_string(f.row + 1) + ":" + what + " over columns " + std::to_string(first) + "-" +
                std::to_string(last) + wraps + " is " + std::to_string(f.columns) +
                " stitches long, longer than the float limit of " + std::to_string(maxFloat) +
                " stitches (long floats snag: catch it or " + fix + ")"};
}

}  // namespace

std::vector<ChartWarning> chartWarnings(const Chart& chart, const ChartCell& cell, int maxFloat) {
    std::vector<ChartWarning> out;
    // Step 1: the floats longer than the limit, each at its row's line.
    for (const ChartFloat& f : cell.floats)
        if (f.columns > maxFloat) out.push_back(longFloat(chart, f, maxFloat));
    // Step 2: the repeat knitted taller than drawn (intarsia areas that wander).
    std::string stacked = stackingWarning(chart, cell.stacking);
    if (!stacked.empty()) out.push_back({0, std::move(stacked)});
    return out;
}

std::string chartWarningMessage(const Chart& chart, const ChartWarning& warning) {
    const std::string where = warning.line > 0 ? ":" + std::to_string(warning.line) : std::string();
    return chart.name + where + ": " + warning.text;
}

}  // namespace knit
