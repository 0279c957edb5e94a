// main.cpp — speed_vs_error: the measurement program behind docs/speed-vs-error.md.
//
// One program that measures seven speed-against-error trade-offs of libknit's settings on the
// machine it runs on, then writes the report from those numbers only. Run it through
// scripts/speed-vs-error.sh (builds Release, runs both steps, draws the plots):
//
//   speed_vs_error measure --results R.json --work DIR [--images DIR] [--items 6,1,4,2,3,5]
//                          [--commit HASH] [--dirty 0|1] [--date TEXT] [--command TEXT] [--nproc N]
//                          [--base EARLIER.json]   (update only --items of an earlier run's results)
//   speed_vs_error report  --results R.json --markdown docs/speed-vs-error.md
//                          --images docs/speed-vs-error --data DIR
//
// `measure` (measure.cpp, one item_*.cpp per item) writes every raw number to R.json; `report`
// (report*.cpp) turns R.json into the Markdown report, one data file per plot and a gnuplot
// script (DIR/plots.gp) that draws the SVGs into --images.
//
// Timing: wall clock (steady_clock) around library calls, all cores (TBB default), best of N runs
// (the machine is shared: the minimum is the least disturbed run); the load average is recorded
// before and after every item, and the garment item (6) runs first so its peak memory (VmHWM,
// reset through /proc/self/clear_refs) is its own. Errors are measured against analytic geometry
// (exact helices, cylinders, tori, spheres), against the decoded file, or against a high-sample
// reference image, never estimated.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "measure.hpp"
#include "report.hpp"

namespace {

int runTool(int argc, char** argv) {
    CLI::App app{"Measures libknit's speed-against-error trade-offs and writes docs/speed-vs-error.md"};
    app.require_subcommand(1);
    sve::MeasureOptions mo;
    std::string commit = "unknown", date = "unknown", command = "", dirty = "unknown", nproc = "";
    CLI::App* m = app.add_subcommand("measure", "Run the measurements and write the results JSON");
    m->add_option("--results", mo.results, "Results JSON to write")->required();
    m->add_option("--work", mo.work, "Scratch folder for exported files (removed after each use)");
    m->add_option("--items", mo.items,
                  "Items to run, in order (1..7; 7, the views of docs/views.md, is not in the default list)");
    m->add_option("--commit", commit, "git commit of the measured tree");
    m->add_option("--dirty", dirty, "1 if the tree had uncommitted changes");
    m->add_option("--date", date, "Date of the run");
    m->add_option("--command", command, "The command that produced the run");
    m->add_option("--nproc", nproc, "Output of nproc (processing units available to the run)");
    m->add_option("--garment-repeats", mo.garmentRepeats, "Repeats per side of the garment case (item 6)");
    m->add_option("--images", mo.images, "Folder for the reference renders of item 5 (PNG)");
    m->add_option("--base", mo.base,
                  "Results JSON of an earlier run: keep its other items and header, replace only --items");
    sve::ReportOptions ro;
    CLI::App* rep = app.add_subcommand("report", "Write the Markdown report, plot data and gnuplot script");
    rep->add_option("--results", ro.results, "Results JSON")->required();
    rep->add_option("--markdown", ro.markdown, "Markdown report to write")->required();
    rep->add_option("--images", ro.images, "Folder for the SVG plots (the report links them relative to itself)")
        ->required();
    rep->add_option("--data", ro.data, "Folder for plot data and plots.gp")->required();
    CLI11_PARSE(app, argc, argv);
    try {
        if (m->parsed()) {
            mo.meta = {{"commit", commit},   {"dirty", dirty},    {"date", date},
                       {"command", command}, {"items", mo.items}, {"nproc", nproc}};
            sve::measure(mo);
        } else {
            sve::writeReport(ro);
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "speed_vs_error: error: %s\n", e.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return runTool(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "speed_vs_error: error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "speed_vs_error: error: unknown exception\n");
    }
    return 1;
}
