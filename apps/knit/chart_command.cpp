// `knit chart`: parse the chart, relax it, write the .pyp cell and an optional JSON report.
#include "chart_command.hpp"

#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/chart_warnings.hpp"
#include "knit/export.hpp"
#include "knit/output_transaction.hpp"
#include "knit/pattern.hpp"
#include "path_collisions.hpp"
#include "report.hpp"
#include "setting_flags.hpp"

namespace knit::cli {

void addChartCommand(CLI::App& app, ChartCommand& c) {
    c.command =
        app.add_subcommand("chart", "Relax a stitch chart (.chart/.txt or chart:NAME) into a periodic .pyp cell");
    c.command->add_option("chart", c.chart, "Chart file, or a built-in chart:NAME")->required();
    c.command->add_option("-o,--output", c.output, "Output .pyp file")->required();
    c.command->add_option("--yarn-radius", c.yarnRadius, "Yarn radius (metres)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    c.command->add_option("--report", c.report,
                          "Write a JSON report (size, iterations, min distance, period, every float)");
    c.command
        ->add_option("--max-float", c.maxFloat,
                     "Warn about floats (stranded colourwork, slipped stitches) longer than this many stitches")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
}

namespace {

// Where a float lies, in the knitter's words: chart row (1 = the bottom row) and its line, the
// columns it passes (1 = the leftmost; it may wrap round the repeat).
struct FloatPlace {
    int row = 0, line = 0, first = 0, last = 0;
};
FloatPlace placeOf(const Chart& chart, const ChartFloat& f) {
    return {f.row + 1, chart.rowLine[size_t(f.row)], f.firstColumn + 1,
            (f.firstColumn + f.columns - 1) % chart.width + 1};
}

nlohmann::json floatsOf(const Chart& chart, const ChartPattern& cp, int maxFloat) {
    nlohmann::json floats = nlohmann::json::array();
    for (const ChartFloat& f : cp.cell.floats) {
        const FloatPlace at = placeOf(chart, f);
        floats.push_back({{"row", at.row},
                          {"line", at.line},
                          {"columns", {at.first, at.last}},
                          {"stitches", f.columns},
                          {"colour", f.colour ? std::string(1, f.colour) : std::string()},
                          {"side", f.front ? "front" : "back"},
                          {"stranded", f.stranded},
                          {"carried", f.carried},
                          {"too_long", f.columns > maxFloat}});
    }
    return floats;
}

nlohmann::json reportOf(const Chart& chart, const ChartPattern& cp, int maxFloat) {
    const Pattern& p = cp.relaxed.pattern;
    return {{"chart", chart.name},
            {"stitches", chart.width},
            {"rows", chart.height},
            {"vertices", p.points.size()},
            {"period_m", {p.px, p.py}},
            {"yarn_radius_m", p.radius},
            {"iterations", cp.relaxed.iterations},
            {"converged", cp.relaxed.converged},
            {"min_distance_radii", cp.relaxed.minDistance},
            {"seconds", cp.seconds},
            {"yarns", cp.cell.yarns},
            {"colourwork", chart.colourwork == Colourwork::Stranded   ? "stranded"
                           : chart.colourwork == Colourwork::Intarsia ? "intarsia"
                                                                      : "painted"},
            {"cell_rows", cp.cell.height},  // an odd intarsia chart's cell has its rows twice
            {"rows_stacked",
             {{"times", cp.cell.stacking.times},
              {"areas_wander", cp.cell.stacking.wandering},
              {"why", stackingWarning(chart, cp.cell.stacking)}}},
            {"max_float", maxFloat},
            {"floats", floatsOf(chart, cp, maxFloat)}};
}

// A long relaxation (a large chart) shows its progress on stderr every 10 s; short ones are silent.
RelaxStepFn progressLines(const Chart& chart, int maxIterations) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto shown = start;
    const Chart named = [&] {  // what progressLine reads: the name and size, not the stitches
        Chart c;
        c.name = chart.name;
        c.width = chart.width;
        c.height = chart.height;
        return c;
    }();
    const ChartStacking stacking = chartStacking(chart);
    return [=](const RelaxStep& step) mutable {
        const auto now = Clock::now();
        if (now - shown < std::chrono::seconds(10)) return true;
        shown = now;
        std::fprintf(stderr, "%s\n",
                     progressLine(named, stacking, step.iteration, maxIterations,
                                  std::chrono::duration<double>(now - start).count())
                         .c_str());
        return true;
    };
}

}  // namespace

std::string progressLine(const Chart& chart, const ChartStacking& stacking, int iteration, int maxIterations,
                         double seconds) {
    // The cell's size is what relaxes: a stacked intarsia chart's rows several times over.
    const std::string stacked = stacking.times > 1 ? ": the chart's " + std::to_string(chart.height) + " rows " +
                                                         std::to_string(stacking.times) + " times over"
                                                   : std::string();
    char tail[96];
    std::snprintf(tail, sizeof tail, "): iteration %d of at most %d, %.0f s", iteration, maxIterations, seconds);
    return "knit: relaxing " + chart.name + " (" + std::to_string(stacking.rows) + " rows x " +
           std::to_string(chart.width) + " stitches" + stacked + tail;
}

int runChart(const ChartCommand& c) {
    // Step 1: fail before relaxing: a report path that cannot be written, an output that is the
    // chart itself or the other output.
    checkReportPath(c.report);
    const bool builtin = c.chart.rfind("chart:", 0) == 0;
    refuseCollidingPaths({{"the chart", builtin ? std::string() : c.chart}},
                         {{"-o", c.output}, {"--report", c.report}});
    // After the collisions (an output onto an input is the more useful message).
    refuseOtherFormatName("-o", c.output, "a pattern", ".pyp");
    // Step 2: parse and relax; step 3: write the cell and its report together.
    const Chart chart = builtin ? builtinChart(c.chart) : loadChart(c.chart);
    ChartPatternOptions options;
    options.radius = c.yarnRadius;
    options.onStep = progressLines(chart, options.maxIterations);
    const ChartPattern cp = relaxChart(chart, options);
    for (const ChartWarning& w : chartWarnings(chart, cp.cell, c.maxFloat))
        std::fprintf(stderr, "knit: warning: %s\n", withFlags(chartWarningMessage(chart, w)).c_str());
    OutputTransaction outputs;  // the pattern and its report are committed together
    outputs.run([&] {
        writeFileAtomically(
            outputs.stage(c.output), [&](std::ostream& out) { writePyp(out, cp.relaxed.pattern); }, false);
        if (!c.report.empty())
            writeFileAtomically(
                outputs.stage(c.report),
                [&](std::ostream& out) { out << reportOf(chart, cp, c.maxFloat).dump(2) << '\n'; }, false);
        outputs.commit();
    });
    std::printf("wrote %s (%d x %d stitches, %zu vertices, min distance %.3f r, %.2f s)\n", c.output.c_str(),
                chart.width, chart.height, cp.relaxed.pattern.points.size(), cp.relaxed.minDistance, cp.seconds);
    return 0;
}

}  // namespace knit::cli
