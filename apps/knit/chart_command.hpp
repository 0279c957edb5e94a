// chart_command.hpp — `knit chart CHART.txt -o cell.pyp`: relax a stitch chart into a .pyp cell.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

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

// Relaxes the chart and writes the cell (and the report); prints one line on stdout and a warning
// on stderr per float longer than --max-float stitches.
// Throws knit::Error on bad input.
int runChart(const ChartCommand& chart);

}  // namespace knit::cli
