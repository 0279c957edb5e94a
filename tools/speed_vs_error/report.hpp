// report.hpp — the `report` command: results JSON -> Markdown report, one data file per plot and
// a gnuplot script (plots.gp) drawing the SVGs. Shared by the per-item report writers.
#pragma once
#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common.hpp"

namespace sve {

struct ReportOptions {
    std::string results;   // results JSON (written by `measure`)
    std::string markdown;  // Markdown report to write
    std::string images;    // folder for the SVG plots (the report links them relative to itself)
    std::string data;      // folder for plot data and plots.gp
};

void writeReport(const ReportOptions& options);

// ---- number formatting ----
std::string fmt(double v, int digits = 3);  // %g with `digits` significant digits
std::string fixed(double v, int decimals);  // %f with `decimals` decimals
std::string mb(double bytes);
std::string gib(double bytes);
std::string loadText(const json& l);
std::string str(const json& v);
std::string marks(bool knee, bool def);

// Kneedle (Satopaa et al. 2011) on a decreasing error-vs-cost curve: both axes normalised to
// [0, 1] over the measured range, the score of a point is its distance below the chord from the
// cheapest to the most expensive setting (1 - x - y). Where the curve is flat near its knee
// several points score almost alike, so the knee is the cheapest point scoring within 1% of the
// best (robust to tiny changes of the data or of the sweep).
struct Knee {
    size_t index = 0;
    std::vector<double> score;
};
Knee kneedle(const std::vector<double>& cost, const std::vector<double>& err);
// The values of `key` over `rows` (a timing object gives its best time).
std::vector<double> column(const json& rows, const std::string& key);

struct Report {
    std::ostringstream md;
    std::ostringstream gp;
    std::string dataDir, imageDir, imageRel;
    json summary = json::array();   // rows of the summary table
    double budgetR = std::nan("");  // faceting error of the default tube (yarn radii), from item 2
    int budgetSides = 0;

    void data(const std::string& name, const std::string& text) {
        std::ofstream out(fs::path(dataDir) / name);
        out << text;
    }
    void plotHeader(const std::string& svg, const std::string& title, const std::string& xlabel,
                    const std::string& ylabel, bool logx, bool logy) {
        gp << "\nreset\nset terminal svg size 760,460 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n"
           << "set output '" << (fs::path(imageDir) / svg).string() << "'\n"
           << "set title \"" << title << "\"\nset xlabel \"" << xlabel << "\"\nset ylabel \"" << ylabel << "\"\n"
           << "set grid\nset key top right box opaque\n"
           << (logx ? "set logscale x\n" : "") << (logy ? "set logscale y\nset format y '%g'\n" : "");
    }
    // Two panels side by side sharing the y axis meaning: call panel() before each plot command,
    // endMulti() after the second.
    void multiHeader(const std::string& svg, const std::string& title) {
        gp << "\nreset\nset terminal svg size 1040,440 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n"
           << "set output '" << (fs::path(imageDir) / svg).string() << "'\n"
           << "set multiplot layout 1,2 title \"" << title << "\"\n";
    }
    void panel(const std::string& xlabel, const std::string& ylabel, bool logx, bool logy,
               const std::string& key = "top right") {
        gp << "unset logscale\nset xlabel \"" << xlabel << "\"\nset ylabel \"" << ylabel << "\"\n"
           << "set grid\nset key " << key << " box opaque\nset format x '%g'\nset format y '%g'\n"
           << (logx ? "set logscale x\n" : "") << (logy ? "set logscale y\n" : "");
    }
    void endMulti() { gp << "unset multiplot\n"; }
    // Columns 3 and 4 of `data` against column x, labelled with column 1, and the knee (column kx
    // against 2 of `knee`) circled in red.
    void kneePlot(const std::string& data, const std::string& x, const std::string& title3, const std::string& title4,
                  const std::string& knee, const std::string& kx) {
        gp << "plot " << dat(data) << " using " << x << ":3 with linespoints pt 7 title '" << title3 << "', \\\n  "
           << dat(data) << " using " << x << ":4 with linespoints pt 5 title '" << title4 << "', \\\n  " << dat(data)
           << " using " << x << ":(($3>$4?$3:$4)):1 with labels offset 1.5,0.7 notitle, \\\n  " << dat(knee)
           << " using " << kx << ":2 with points pt 6 ps 3 lw 2 lc rgb 'red' title 'knee'\n";
    }
    std::string dat(const std::string& name) const { return "'" + (fs::path(dataDir) / name).string() + "'"; }
    std::string image(const std::string& file, const std::string& alt) const {
        return "![" + alt + "](" + imageRel + "/" + file + ")\n";
    }
};

// One section per item (report_settings.cpp: 1-3, report_workloads.cpp: 4-6, report_views.cpp: 7).
void reportPlies(Report& rep, const json& j, const json& defaults);
void reportTubes(Report& rep, const json& j, const json& defaults);
void reportDraco(Report& rep, const json& j, const json& defaults);
void reportBaseMesh(Report& rep, const json& j);
void reportRender(Report& rep, const json& j);
void reportGarment(Report& rep, const json& j);
void reportViews(Report& rep, const json& j);  // report_views.cpp: item 7

}  // namespace sve
