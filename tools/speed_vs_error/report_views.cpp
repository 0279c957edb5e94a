// report_views.cpp — the report's section for item 7 (item_views.cpp): level of detail for a view
// against `--detail full` on the garment, from three cameras.
#include <string>
#include <vector>

#include "report.hpp"

namespace sve {

namespace {

std::string percent(const json& v) { return (v.get<double>() >= 0 ? "+" : "") + fixed(100 * v.get<double>(), 1) + "%"; }

std::string meanText(const json& rel) { return percent(rel[0]) + ", " + percent(rel[1]) + ", " + percent(rel[2]); }

}  // namespace

void reportViews(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const std::vector<std::string> cameras{"far", "mid", "close"};
    const double fullScene = j["full_scene_seconds"];
    md << "## 7. Level of detail for a view (`--detail view` against `--detail full`)\n\n"
       << "The garment of item 6 (the drape at 256 x 256 quads, the stockinette 660 x 660), front-lit, 320 x 240, "
          "32 samples per pixel, from three cameras: far (the default framing), mid (eye (0.04, 0.22, 0) looking at "
          "the top of the drape, ~6.7 cm away, grazing) and close (eye (0.015, 0.19, 0), ~2.7 cm). The full scene "
          "(every ply, "
       << fmt(j["far"]["full"]["segments"].get<double>(), 4) << " segments) is built once (" << fixed(fullScene, 1)
       << " s, peak " << gib(j["full_peak_bytes"]) << " GiB) and rendered from each camera at seed 1 (the reference) "
       << "and seed 2 (**the noise floor**: how close another full render comes). `--detail view` scenes are built "
          "per camera with the level thresholds scaled by 0.5, 1 (the default) and 2, and the default again at seed "
          "2; their time is scene + render, the full render's is the shared scene + its render. Errors against the "
          "reference: mean radiance per channel, and the RMSE of 4 x 4 block mean luminances over the reference's "
          "mean luminance (docs/views.md).\n\n"
       << "| camera | detail | seed | segments (of full) | surface triangles | time (s) | faster | peak (GiB) | mean "
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
       << "Peak memory of a view is the process's peak resident memory, reset before each view (the full scene is "
          "gone by then). A view render is within the render noise of `--detail full` when its block RMSE is no "
          "larger than the noise floor's.\n\n";
}

}  // namespace sve
