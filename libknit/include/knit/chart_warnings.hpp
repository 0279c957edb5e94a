// knit/chart_warnings.hpp — a designer's warnings on a chart that builds (issue 25): floats longer
// than the float limit, and an intarsia repeat knitted taller than drawn because its areas wander.
//
// The words are the library's, the same for every front end: `knit chart` prints each after
// "knit: warning: " (the float limit spelled --max-float), the Python module warns with
// knit.ChartWarning (spelled max_float), the Blender add-on reports them from Apply Knit.
#pragma once
#include <string>
#include <vector>

#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"

namespace knit {

struct ChartWarning {
    int line = 0;      // the chart's line it is about (a float's row), 0 for the chart as a whole
    std::string text;  // what and why, naming the row and columns in the knitter's numbering
};

// The floats longer than maxFloat stitches, in the order of cell.floats, then the note of rows
// stacked because the areas wander (stackingWarning); empty when nothing is worth saying.
std::vector<ChartWarning> chartWarnings(const Chart& chart, const ChartCell& cell, int maxFloat);

// "NAME:LINE: TEXT", or "NAME: TEXT" for the chart as a whole (as knit::Error names a place).
std::string chartWarningMessage(const Chart& chart, const ChartWarning& warning);

}  // namespace knit
