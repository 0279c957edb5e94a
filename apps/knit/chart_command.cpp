// `knit chart`: parse the chart, relax it, write the .pyp cell and an optional JSON report.
#include "chart_command.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/export.hpp"
#include "knit/output_transaction.hpp"
#include "knit/pattern.hpp"
#include "path_collisions.hpp"
#include "report.hpp"

namespace knit::cli {

void addChartCommand(CLI::App& app, ChartCommand& c) {
    c.command =
        app.add_subcommand("chart", "Relax a stitch chart (.chart/.txt or chart:NAME) into a periodic .pyp cell");
    c.command->add_option("chart", c.chart, "Chart file, or a built-in chart:NAME")->required();
    c.command->add_option("-o,--output", c.output, "Output .pyp file")->required();
    c.command->add_option("--yarn-radius", c.yarnRadius, "Yarn radius (metres)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    c.command->add_option("--report", c.report, "Write a JSON report (size, iterations, min distance, period)");
}

namespace {

nlohmann::json reportOf(const Chart& chart, const ChartPattern& cp) {
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
            {"seconds", cp.seconds}};
}

}  // namespace

int runChart(const ChartCommand& c) {
    // Step 1: fail before relaxing: a report path that cannot be written, an output that is the
    // chart itself or the other output.
    checkReportPath(c.report);
    const bool builtin = c.chart.rfind("chart:", 0) == 0;
    refuseCollidingPaths({{"the chart", builtin ? std::string() : c.chart}},
                         {{"-o", c.output}, {"--report", c.report}});
    // Step 2: parse and relax; step 3: write the cell and its report together.
    const Chart chart = builtin ? builtinChart(c.chart) : loadChart(c.chart);
    ChartPatternOptions options;
    options.radius = c.yarnRadius;
    const ChartPattern cp = relaxChart(chart, options);
    OutputTransaction outputs;  // the pattern and its report are committed together
    outputs.run([&] {
        writeFileAtomically(
            outputs.stage(c.output), [&](std::ostream& out) { writePyp(out, cp.relaxed.pattern); }, false);
        if (!c.report.empty())
            writeFileAtomically(
                outputs.stage(c.report), [&](std::ostream& out) { out << reportOf(chart, cp).dump(2) << '\n'; }, false);
        outputs.commit();
    });
    std::printf("wrote %s (%d x %d stitches, %zu vertices, min distance %.3f r, %.2f s)\n", c.output.c_str(),
                chart.width, chart.height, cp.relaxed.pattern.points.size(), cp.relaxed.minDistance, cp.seconds);
    return 0;
}

}  // namespace knit::cli
