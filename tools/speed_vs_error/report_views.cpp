// report_views.cpp — the report's section for item 7 (item_views.cpp): level of detail for a view
// against `--detail full` on the garment, from four cameras; then what a view costs against the
// camera's distance (memory and time of the default view beside the full render's).
#include <cmath>
#include <string>
#include <vector>

#include "report.hpp"

namespace sve {

namespace {

std::string percent(const json& v) { return (v.get<double>() >= 0 ? "+" : "") + fixed(100 * v.get<double>(), 1) + "%"; }

std::string meanText(const json& rel) { return percent(rel[0]) + ", " + percent(rel[1]) + ", " + percent(rel[2]); }

// The camera's distance to its target in metres (results from before it was recorded: from the
// full render's eye and target).
double cameraDistance(const json& cam) {
    if (cam.contains("distance_m")) return cam["distance_m"];
    const json& e = cam["full"]["eye"];
    const json& t = cam["full"]["target"];
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(e[k].get<double>() - t[k].get<double>(), 2);
    return std::sqrt(d2);
}

// The default view's run (thresholds x1, seed 1) of a camera; null when it is missing.
const json* defaultView(const json& cam) {
    for (const json& v : cam["view"])
        if (v["threshold_scale"].get<double>() == 1.0 && v["seed"].get<int>() == 1) return &v;
    return nullptr;
}

// How the views' peak memory was measured: before the full scene (results with "views_before_full")
// or after it (then it includes what the process kept from the full scene: an upper bound).
std::string viewPeakText(const json& j) {
    if (j.value("views_before_full", false))
        return "The view's peak memory is the process's peak resident memory, reset before the view's scene is built; "
               "the views run before the full scene is built, so it is the view's own plus what the process holds "
               "then (the mesh, the pattern and the earlier views' images: the `resident_before_bytes` of "
               "results.json).";
    return "The view's peak memory is the process's peak resident memory, reset before the view's scene is built: "
           "this run measured the views after the full renders, so it still counts what the process holds after them "
           "(the reference images, and freed memory the allocator keeps): an upper bound; `knit render --detail "
           "view` in a process of its own peaks lower (docs/views.md, \"Peak memory against camera distance\").";
}

// The run that measured the section (its date, commit, command and the load average during it):
// it differs from the report's header when the item was updated alone (KNIT_SVE_UPDATE=1).
void reportRun(Report& rep, const json& j) {
    if (!j.contains("run")) return;
    const json& run = j["run"];
    std::ostringstream& md = rep.md;
    md << "**This section's run**: " << run.value("date", std::string("?")) << ", commit `"
       << run.value("commit", std::string("?")) << "`"
       << (run.value("dirty", std::string()) == "1" ? " (dirty tree)" : "") << ", "
       << fixed(j["item_seconds"].get<double>() / 60, 0) << " min, reproduced by `"
       << run.value("command", std::string("?")) << "`. 1-minute load average ";
    if (j.contains("load_during") && j["load_during"].contains("mean"))
        md << fixed(j["load_during"]["min"], 1) << "-" << fixed(j["load_during"]["max"], 1) << " (mean "
           << fixed(j["load_during"]["mean"], 1) << ", sampled every 5 s) during it";
    else md << loadText(j["load_before"]) << " before and " << loadText(j["load_after"]) << " after it";
    md << " on " << run.value("nproc", std::string("?"))
       << " processing units: other engineers were building and testing on the machine, so the times are inflated "
          "(by the load, not evenly); segment counts, peak memory and image errors do not depend on it.\n\n";
}

// Memory and time of the default view against the camera's distance, beside the full render's
// (its scene is shared by the cameras: its time is that scene plus the camera's render).
void reportDistance(Report& rep, const json& j, const std::vector<std::string>& cameras) {
    std::ostringstream& md = rep.md;
    const double fullScene = j["full_scene_seconds"];
    md << "### What a view costs against the camera's distance\n\n"
       << "The default view (thresholds x1, seed 1) of each camera against `--detail full` (peak "
       << gib(j["full_peak_bytes"]) << " GiB for any camera: every ply of the garment is built and traced). "
       << viewPeakText(j)
       << " The view's time is its scene plus its render, the full render's the shared scene plus "
          "the camera's render.\n\n"
       << "| camera | distance to target | view peak (MiB) | full peak (GiB) | less memory | view time (s) | full "
          "time (s) | faster | block RMSE (full at seed 2) |\n|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    std::ostringstream dd;
    dd << "# camera distance_m view_peak_gib full_peak_gib\n";
    for (const std::string& c : cameras) {
        if (!j.contains(c)) continue;
        const json* v = defaultView(j[c]);
        if (v == nullptr) continue;
        const double distance = cameraDistance(j[c]);
        const double viewPeak = (*v)["peak_bytes"], fullPeak = j["full_peak_bytes"];
        const double viewTime = (*v)["seconds"], fullTime = fullScene + j[c]["full"]["render_seconds"].get<double>();
        const json& full = j[c]["full"];
        md << "| " << c << " | " << (distance >= 0.1 ? fixed(distance, 2) + " m" : fixed(100 * distance, 1) + " cm")
           << " | " << fixed(viewPeak / (1 << 20), 0) << " | " << gib(fullPeak) << " | "
           << fixed(fullPeak / viewPeak, 0) << "x | " << fixed(viewTime, 1) << " | " << fixed(fullTime, 1) << " | "
           << fixed(fullTime / viewTime, 1) << "x | " << fixed(100 * (*v)["block_rmse_relative"].get<double>(), 1)
           << "% ("
           << (full.contains("seed2") ? fixed(100 * full["seed2"]["block_rmse_relative"].get<double>(), 1) + "%"
                                      : std::string("-"))
           << ") |\n";
        dd << c << " " << distance << " " << viewPeak / double(1 << 30) << " " << fullPeak / double(1 << 30) << "\n";
    }
    rep.data("views_memory.dat", dd.str());
    rep.plotHeader("views-memory.svg", "Peak memory of a view against the camera's distance",
                   "camera distance to its target (m)", "peak resident memory (GiB)", true, true);
    rep.gp << "plot " << rep.dat("views_memory.dat") << " using 2:3 with linespoints pt 7 title '--detail view', \\\n  "
           << rep.dat("views_memory.dat") << " using 2:3:1 with labels offset 1.5,0.7 notitle, \\\n  "
           << rep.dat("views_memory.dat") << " using 2:4 with lines dt 2 title '--detail full'\n";
    md << "\n" << rep.image("views-memory.svg", "peak memory of a view against the camera's distance") << "\n";
}

}  // namespace

void reportViews(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const std::vector<std::string> cameras{"far", "mid", "close", "1cm"};
    const double fullScene = j["full_scene_seconds"];
    md << "## 7. Level of detail for a view (`--detail view` against `--detail full`)\n\n"
       << "The garment of item 6 (the drape at 256 x 256 quads, the stockinette 660 x 660), front-lit, 320 x 240, "
          "32 samples per pixel, from up to four cameras: far (the default framing), mid (eye (0.04, 0.22, 0) "
          "looking at the top of the drape, ~6.7 cm away, grazing), close (eye (0.015, 0.19, 0), ~2.7 cm) and 1cm "
          "(eye (0.00541, 0.17511, 0), 1 cm; results from before it was added have three). The full scene "
          "(every ply, "
       << fmt(j["far"]["full"]["segments"].get<double>(), 4) << " segments) is built once (" << fixed(fullScene, 1)
       << " s, peak " << gib(j["full_peak_bytes"]) << " GiB) and rendered from each camera at seed 1 (the reference) "
       << "and seed 2 (**the noise floor**: how close another full render comes). `--detail view` scenes are built "
          "per camera with the level thresholds scaled by 0.5, 1 (the default) and 2, and the default again at seed "
          "2; their time is scene + render, the full render's is the shared scene + its render. Errors against the "
          "reference: mean radiance per channel, and the RMSE of 4 x 4 block mean luminances over the reference's "
          "mean luminance (docs/views.md).\n\n";
    reportRun(rep, j);
    md << "| camera | detail | seed | segments (of full) | surface triangles | time (s) | faster | peak (GiB) | mean "
          "r, "
          "g, b | block RMSE |\n|---|---|---:|---:|---:|---:|---:|---:|---|---:|\n";
    rep.plotHeader("views.svg", "Level of detail for a view: block error against time", "seconds (scene + render)",
                   "4 x 4 block RMSE (% of the mean)", true, false);
    std::string plot = "plot ";
    for (size_t k = 0; k < cameras.size(); ++k) {
        const std::string& c = cameras[k];
        if (!j.contains(c)) continue;
        const json& full = j[c]["full"];
        const double fullTime = fullScene + full["render_seconds"].get<double>();
        md << "| " << c << " | full | 1 | " << full["segments"].get<size_t>() << " (100%) | 0 | " << fixed(fullTime, 1)
           << " | 1x | " << gib(j["full_peak_bytes"]) << " | reference | - |\n";
        if (full.contains("seed2"))
            md << "| " << c << " | full | 2 | (noise floor) | | | | | " << meanText(full["seed2"]["mean_relative"])
               << " | **" << fixed(100 * full["seed2"]["block_rmse_relative"].get<double>(), 1) << "%** |\n";
        std::ostringstream dd;
        dd << "# scale seconds block_rmse_percent\n";
        for (const json& v : j[c]["view"]) {
            const double t = v["seconds"];
            md << "| " << c << " | view x" << fmt(v["threshold_scale"].get<double>(), 2) << " | " << v["seed"] << " | "
               << v["segments"].get<size_t>() << " (" << fmt(100 * v["segments_fraction"].get<double>(), 2) << "%) | "
               << v["surface_triangles"].get<size_t>() << " | " << fixed(t, 1) << " | " << fixed(fullTime / t, 1)
               << "x | " << gib(v["peak_bytes"]) << " | " << meanText(v["mean_relative"]) << " | "
               << fixed(100 * v["block_rmse_relative"].get<double>(), 1) << "% |\n";
            if (v["seed"].get<int>() == 1)
                dd << "\"x" << fmt(v["threshold_scale"].get<double>(), 2) << "\" " << t << " "
                   << 100 * v["block_rmse_relative"].get<double>() << "\n";
        }
        rep.data("views_" + c + ".dat", dd.str());
        plot += std::string(k ? ", \\\n  " : "") + rep.dat("views_" + c + ".dat") + " using 2:3 with linespoints pt " +
                std::to_string(5 + 2 * int(k)) + " title '" + c + "', \\\n  " + rep.dat("views_" + c + ".dat") +
                " using 2:3:1 with labels offset 1.5,0.7 notitle";
    }
    rep.gp << plot << "\n";
    md << "\n"
       << rep.image("views.svg", "level of detail for a view: block error against time") << "\n"
       << viewPeakText(j)
       << " A view render is within the render noise of `--detail full` when its block RMSE is no larger than the "
          "noise floor's.\n\n";
    reportDistance(rep, j, cameras);
}

}  // namespace sve
