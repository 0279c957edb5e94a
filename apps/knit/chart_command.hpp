// chart_command.hpp — `knit chart CHART.txt -o cell.pyp`: relax a stitch chart into a .pyp cell.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"

namespace knit::cli {

struct ChartCommand {
    CLI::App* command = nullptr;  // set by addChartCommand
    std::string chart;            // chart file or built-in chart:NAME
    std::string output;           // .pyp path (required)
    double yarnRadius = 0.001;    // metres
    std::string report;           // optional JSON report path
    int maxFloat = 5;             // floats longer than this many stitches are warned about
};

// Registers the subcommand and its flags on `app`, bound to `chart` (which must outlive parsing).
void addChartCommand(CLI::App& app, ChartCommand& chart);

// Relaxes the chart and writes the cell (and the report); prints one line on stdout and the
// chart's warnings (knit/chart_warnings.hpp: each float longer than --max-float stitches, the
// rows stacked) on stderr.
// Throws knit::Error on bad input.
int runChart(const ChartCommand& chart);

// The progress line a long relaxation prints every 10 s: the size of the cell that relaxes (a
// stacked intarsia chart's rows `stacking.times` over, saying so), the iteration, the seconds.
std::string progressLine(const Chart& chart, const ChartStacking& stacking, int iteration, int maxIterations,
                         double seconds);

}  // namespace knit::cli
