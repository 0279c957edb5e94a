// report_workloads.cpp — report sections of the workloads: base-mesh resolution (item 4), render
// modes (item 5) and garment scale (item 6).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "report.hpp"

namespace sve {

// ---- 4 ----
void reportBaseMesh(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const double budget = std::isfinite(rep.budgetR) ? rep.budgetR : 0.04;
    md << "## 4. Base-mesh resolution (how coarse the mesh under the knit may be)\n\n"
       << "**Error**: every bound yarn vertex has a triangle, barycentrics and a height h; its (u, v) is the "
          "barycentric blend of the triangle's UVs. The exact position is S(u, v) + h n(u, v) on the analytic surface "
          "the procedural mesh samples (cylinder: (r cos 2 pi u, r sin 2 pi u, v H); sphere: latitude-longitude; "
          "exact unit normals); the mapped position is `knit::evaluateBinding` on the mesh (vertex normals from "
          "`knit::vertexNormals`). Max and RMS of the distance over all yarn vertices, in yarn radii. The chord sag "
          "r (1 - cos(pi / resolution)) of the mesh's edges around the surface is listed for comparison.\n\n"
       << "**Speed**: `buildUvGrid` + `bindYarns` (the binding, computed once per rest mesh), best of the runs; "
          "`evaluateBinding` (once per animation frame) for reference.\n\n";
    rep.plotHeader("base-mesh.svg", "Base-mesh resolution: binding time against mapping error (labels: quads around)",
                   "UV grid + binding time (ms, best of runs)", "max mapping error (yarn radii)", true, true);
    std::string plot = "plot ";
    int series = 0;
    std::string guidance;
    for (const auto& [name, s] : j["surfaces"].items()) {
        const json& rows = s["rows"];
        const double R = s["yarn_radius_m"], radius = s["radius_m"];
        std::ostringstream dd;
        dd << "# res_u bind_ms max_error_R\n";
        for (const json& r : rows)
            dd << r["res_u"] << " " << r["bind_total_seconds"].get<double>() * 1e3 << " " << r["max_error_R"] << "\n";
        rep.data("mesh_" + name + ".dat", dd.str());
        int pick = -1;
        for (size_t i = 0; i < rows.size(); ++i)
            if (pick < 0 && rows[i]["max_error_R"].get<double>() <= budget) pick = int(i);
        plot += std::string(series ? ", \\\n  " : "") + rep.dat("mesh_" + name + ".dat") +
                " using 2:3 with linespoints pt " + std::to_string(series ? 5 : 7) + " title '" + name + "', \\\n  " +
                rep.dat("mesh_" + name + ".dat") + " using 2:3:1 with labels offset 1.5,0.7 notitle";
        ++series;
        md << "**" << name << "** (radius " << fmt(radius) << " m"
           << (s.contains("height_m") ? ", height " + fmt(s["height_m"]) + " m" : "") << ", repeats "
           << fmt(s["repeats"][0]) << " x " << fmt(s["repeats"][1]) << ", yarn radius " << fmt(R * 1e3) << " mm):\n\n"
           << "| resolution (u x v) | triangles | mesh edge (stitches) | max error (R) | RMS error (R) | chord sag (R) "
              "| grid + bind (ms) | M yarn vertices/s | evaluate (ms) |\n"
           << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (size_t i = 0; i < rows.size(); ++i) {
            const json& r = rows[i];
            const double sag = radius * (1 - std::cos(kPi / r["res_u"].get<double>())) / R;
            md << "| " << r["res_u"] << " x " << r["res_v"] << (int(i) == pick ? " (coarsest in budget)" : "") << " | "
               << r["triangles"].get<size_t>() << " | " << fixed(r["edge_in_stitches"], 2) << " | "
               << fmt(r["max_error_R"]) << " | " << fmt(r["rms_error_R"]) << " | " << fmt(sag) << " | "
               << fixed(r["bind_total_seconds"].get<double>() * 1e3, 1) << " | "
               << fixed(r["yarn_vertices_per_second_bind"].get<double>() / 1e6, 1) << " | "
               << fixed(r["evaluate_seconds"]["best"].get<double>() * 1e3, 2) << " |\n";
        }
        const json& lo = rows[0];
        const json& hi = rows[rows.size() - 1];
        md << "\n";
        if (pick >= 0) {
            const json& k = rows[size_t(pick)];
            md << "Coarsest " << name << " mesh whose mapping error stays within the budget (" << fmt(budget)
               << " R, the default tube's faceting error): **" << k["res_u"] << " x " << k["res_v"] << "** (mesh edge "
               << fixed(k["edge_in_stitches"], 2) << " stitches, "
               << fixed(2 * kPi * radius / k["res_u"].get<double>() / R, 1) << " yarn radii, max error "
               << fmt(k["max_error_R"]) << " R, grid + bind " << fixed(k["bind_total_seconds"].get<double>() * 1e3, 1)
               << " ms). ";
            guidance += (guidance.empty() ? "" : ", ") + name + " " + std::to_string(k["res_u"].get<int>()) + " x " +
                        std::to_string(k["res_v"].get<int>());
        } else {
            md << "No measured " << name << " resolution is within the budget (" << fmt(budget) << " R). ";
        }
        md << "From " << lo["res_u"] << " to " << hi["res_u"] << " quads around, the error fell "
           << fixed(lo["max_error_R"].get<double>() / hi["max_error_R"].get<double>(), 0)
           << "x while grid + binding time grew "
           << fixed(hi["bind_total_seconds"].get<double>() / lo["bind_total_seconds"].get<double>(), 1) << "x.\n\n";
        rep.summary.push_back(
            {{"setting", "base mesh resolution (" + name + ", an input)"},
             {"rule", "coarsest mesh with error <= the default tube's faceting"},
             {"knee", pick >= 0 ? std::to_string(rows[size_t(pick)]["res_u"].get<int>()) + " x " +
                                      std::to_string(rows[size_t(pick)]["res_v"].get<int>())
                                : std::string("none measured")},
             {"default", "-"},
             {"error", pick >= 0 ? fmt(rows[size_t(pick)]["max_error_R"]) + " R max mapping error" : "-"}});
    }
    rep.gp << plot << "\n";
    md << rep.image("base-mesh.svg", "base mesh resolution: binding time against mapping error") << "\n"
       << "The mapping error is the mesh's chord error (it falls with the square of the edge length: on the cylinder "
          "it equals the chord sag column) plus the vertex normals' error times the height; the sphere's is larger "
          "(curved in both directions, longer diagonals, pole fans). Binding time grows only slowly with the mesh, so "
          "a finer base mesh is cheap: as a rule, an edge of length e on a surface of curvature radius rho costs "
          "about e^2 / (8 rho) of error, so keep e <= sqrt(8 rho E) for an error budget E. There is no library "
          "default to change (meshes are inputs; the built-in meshes' 32 x 32 is only a demo size).\n\n";
}

// ---- 5 ----
void reportRender(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const json& s = j["scene"];
    const int refSpp = j["reference_spp"];
    md << "## 5. Render modes (`knit render --mode curves|tubes|grid`)\n\n"
       << "The stockinette on a " << fmt(s["plane_m"].get<double>() * 100) << " cm plane ("
       << s["ply_vertices"].get<size_t>() << " ply vertices, " << s["cells"].get<size_t>() << " grid cells), "
       << j["light"].get<std::string>() << "-lit, " << j["width"] << " x " << j["height"]
       << " pixels, rendered with `knit::renderScene` at 1..64 samples per pixel (seed 1) and compared "
          "(`knit::compareImages`: luminance RMSE over pixels, here divided by the reference's mean luminance) with a "
          "reference of the same mode at "
       << refSpp
       << " spp (another seed). The reference's own noise adds "
          "sqrt(1 + spp / "
       << refSpp << ") to the measured RMSE (" << fixed(100 * (std::sqrt(1 + 64.0 / refSpp) - 1), 0)
       << "% at 64 spp). Memory: the mode's scene memory "
          "(Embree BVH + our intersection buffers, `TraceMemory::sceneBytes`); tubes use "
       << j["tube_sides"] << " sides.\n\n"
       << "| mode | spp | relative RMSE | render (s) | us per sample | M rays/s |\n|---|---:|---:|---:|---:|---:|\n";
    std::string plot = "plot ";
    int series = 0;
    std::ostringstream mem, pics;
    mem << "| mode | scene memory (MB) | Embree (MB) | geometry (MB) | primitives | build (s) | us per sample (spp >= "
           "4, median) | RMSE^2 x time (lower is better) | reference vs curves reference | of which noise alone |\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string mode : {"curves", "tubes", "grid"}) {
        if (!j["modes"].contains(mode)) continue;
        const json& m = j["modes"][mode];
        std::ostringstream dd;
        dd << "# spp render_s relative_rmse\n";
        std::vector<double> eff, us;
        for (const json& r : m["rows"]) {
            dd << r["spp"] << " " << r["render_seconds"] << " " << r["relative_rmse"] << "\n";
            md << "| " << mode << " | " << r["spp"] << " | " << fixed(100 * r["relative_rmse"].get<double>(), 2)
               << "% | " << fmt(r["render_seconds"]) << " | " << fixed(r["us_per_sample"], 2) << " | "
               << fixed(r["rays_per_second"].get<double>() / 1e6, 2) << " |\n";
            if (r["spp"].get<int>() >= 4) {
                eff.push_back(std::pow(r["relative_rmse"].get<double>(), 2) * r["render_seconds"].get<double>());
                us.push_back(r["us_per_sample"]);
            }
        }
        std::sort(eff.begin(), eff.end());
        std::sort(us.begin(), us.end());
        rep.data("render_" + mode + ".dat", dd.str());
        plot += std::string(series ? ", \\\n  " : "") + rep.dat("render_" + mode + ".dat") +
                " using 2:3 with linespoints pt " + std::to_string(5 + 2 * series) + " title '" + mode + " (scene " +
                mb(m["scene_bytes"]) + " MB)', \\\n  " + rep.dat("render_" + mode + ".dat") +
                " using 2:3:1 with labels offset 1.5,0.7 notitle";
        ++series;
        mem << "| " << mode << " | " << mb(m["scene_bytes"]) << " | " << mb(m["embree_bytes"]) << " | "
            << mb(m["geometry_bytes"]) << " | " << m["primitives"].get<size_t>() << " | " << fmt(m["build_seconds"])
            << " | " << (us.empty() ? std::string("-") : fixed(us[us.size() / 2], 2)) << " | "
            << (eff.empty() ? std::string("-") : fmt(eff[eff.size() / 2])) << " | "
            << (m.contains("reference_vs_curves_relative_rmse")
                    ? fixed(100 * m["reference_vs_curves_relative_rmse"].get<double>(), 2) + "%"
                    : std::string("-"))
            << " | "
            << (m.contains("reference_noise_relative_rmse")
                    ? fixed(100 * m["reference_noise_relative_rmse"].get<double>(), 2) + "%"
                    : std::string("-"))
            << " |\n";
        if (m.contains("reference_png"))
            pics << "| ![" << mode << " reference](" << rep.imageRel << "/" << m["reference_png"].get<std::string>()
                 << ") ";
    }
    rep.plotHeader("render-modes.svg", "Render modes: time against image error (labels: samples per pixel)",
                   "render time of the image (s)", "RMSE / mean luminance of the reference", true, true);
    rep.gp << plot << "\n";
    md << "\n" << mem.str() << "\n" << rep.image("render-modes.svg", "render modes: time against RMSE") << "\n";
    if (!pics.str().empty()) {
        md << "References (" << refSpp << " spp):\n\n";
        for (const std::string mode : {"curves", "tubes", "grid"})
            if (j["modes"].contains(mode)) md << "| " << mode << " ";
        md << "|\n";
        for (size_t i = 0; i < j["modes"].size(); ++i) md << "|---";
        md << "|\n" << pics.str() << "|\n\n";
    }
    md << "RMSE falls like 1/sqrt(spp) in every mode (Monte Carlo noise), so the modes differ by cost per sample and "
          "memory: RMSE^2 x time (median over spp >= 4) is the inverse efficiency, lower is better. The last two "
          "columns compare the modes' references with the curves reference: the measured difference (geometry plus the "
          "references' own noise) and what the noise alone would give (the 1-spp errors scaled to the reference's "
          "spp); "
          "the excess is the geometric difference between the modes (tube faceting, the grid mode's trimmed cylinders "
          "against Embree's round curves).\n\n";
}

// ---- 6 ----
void reportGarment(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const double yv = j["yarn_vertices"], pv = j["ply_vertices"], total = j["total_seconds"], cpu = j["cpu_seconds"];
    const int threads = j["threads"];
    std::ostringstream dd;
    dd << "# stage wall cpu\n";
    md << "## 6. Garment scale: the whole pipeline to a plies GLB\n\n"
       << "The stockinette tiled " << j["repeats"] << " x " << j["repeats"] << " over the built-in drape ("
       << j["mesh"]["res"] << " x " << j["mesh"]["res"] << " quads, " << j["mesh"]["triangles"].get<size_t>()
       << " triangles, " << fmt(j["mesh"]["size_m"]) << " m sheet): **" << j["cells"].get<size_t>()
       << " pattern cells, " << j["yarn_vertices"].get<size_t>() << " yarn vertices, "
       << j["ply_vertices"].get<size_t>() << " ply vertices** (" << j["plies"] << " plies, " << j["samples_per_turn"]
       << " samples per turn, yarn radius " << fmt(j["yarn_radius_m"].get<double>() * 1e3, 2)
       << " mm). `knit::buildScene` (in-memory pattern and mesh, "
          "`buildPlies = false`), then `knit::exportScene` to a plies GLB: stage `plies_glb` generates the plies "
          "(resampling, frames, helices), converts them to float32 and writes them chunk by chunk in a TBB pipeline, "
          "without ever holding all plies (`knit build` does the same for .glb / .gltf); one non-indexed LINE_STRIP "
          "per "
          "ply curve with `_RADIUS`. One run, "
       << threads << " hardware threads. CPU = user + system time of the process during the stage (all threads).\n\n"
       << "| stage | wall (s) | share | CPU (s) | cores used | M vertices/s | ns per yarn vertex "
          "|\n|---|---:|---:|---:|---:|---:|---:|\n";
    std::vector<std::pair<double, std::string>> big;
    for (const json& s : j["stages"]) {
        const std::string name = s["stage"];
        const double t = s["seconds"], c = s["cpu_seconds"];
        const bool perPly = name == "plies_glb";
        const double items = perPly ? pv : yv;
        big.emplace_back(t, name);
        dd << "\"" << name << "\" " << t << " " << std::max(c, 0.0) << "\n";
        md << "| " << name << " | " << fixed(t, 3) << " | " << fixed(100 * t / total, 1) << "% | "
           << (c >= 0 ? fixed(c, 2) : std::string("-")) << " | "
           << (c >= 0 && t > 0 ? fixed(c / t, 2) : std::string("-")) << " | "
           << fixed(items / std::max(t, 1e-12) / 1e6, 1) << (perPly ? " (ply)" : " (yarn)") << " | "
           << fixed(t / yv * 1e9, 1) << " |\n";
    }
    md << "| **total** | **" << fixed(total, 2) << "** | 100% | " << fixed(cpu, 2) << " | " << fixed(cpu / total, 2)
       << " | " << fixed(yv / total / 1e6, 2) << " (yarn) | " << fixed(total / yv * 1e9, 1) << " |\n\n";
    std::sort(big.rbegin(), big.rend());
    rep.data("garment.dat", dd.str());
    rep.plotHeader("garment.svg", "Garment scale: time per stage", "", "seconds", false, false);
    rep.gp << "set termoption noenhanced\nset style data histograms\nset style histogram clustered gap 1\nset style "
              "fill solid 0.7 border -1\n"
           << "set xtics rotate by -30\nset key top left\nplot " << rep.dat("garment.dat")
           << " using 2:xtic(1) lc rgb '#4477aa' title 'wall', '' using 3 lc rgb '#ee8866' title 'CPU (all threads)'\n";
    const double target = 5.0 * yv / 1e7;
    // Stages that kept to about one core while the process as a whole got clearly more look serial:
    // on an idle machine they cannot go below their CPU time.
    std::string serialText;
    double serialCpu = 0;
    if (cpu / total > 1.2) {
        std::string names;
        for (const json& s : j["stages"])
            if (s["seconds"].get<double>() > 0.05 * total && s["cpu_seconds"].get<double>() >= 0 &&
                s["cpu_seconds"].get<double>() < 1.1 * s["seconds"].get<double>()) {
                names += (names.empty() ? "" : ", ") + s["stage"].get<std::string>();
                serialCpu += s["cpu_seconds"].get<double>();
            }
        if (!names.empty())
            serialText = " Stages that used about one core while the process averaged " + fixed(cpu / total, 2) +
                         " look serial (" + names + ": " + fixed(serialCpu, 2) +
                         " s of CPU that a second core does not shorten).";
    }
    const double idle =
        (cpu - serialCpu) / threads +
        serialCpu;  // lower bound of the idle-machine wall time  // lower bound of the wall time with all cores to ourselves
    md << rep.image("garment.svg", "garment scale: seconds per stage") << "\n"
       << "Peak resident memory (VmHWM"
       << (j["reset_peak_ok"].get<bool>() ? ", reset before the run" : ", could not be reset: includes earlier items")
       << "): **" << gib(j["peak_bytes"]) << " GiB** (" << fixed(j["peak_bytes"].get<double>() / yv, 0)
       << " bytes per yarn vertex; " << gib(j["peak_after_build_bytes"]) << " GiB after `buildScene`); GLB "
       << mb(j["glb_bytes"]) << " MB. Cost per yarn vertex: " << fixed(total / yv * 1e9, 0) << " ns wall, "
       << fixed(cpu / yv * 1e9, 0) << " ns CPU.\n\n"
       << "**Target** (<= 5 s for 10M yarn vertices to a plies GLB on 2 cores, i.e. " << fixed(target, 2)
       << " s for these " << fixed(yv / 1e6, 2) << "M): **" << (total <= target ? "met" : "not met")
       << "**: " << fixed(total, 2) << " s wall, " << fixed(total / target, 2) << "x the target. ";
    if (total <= target) {
        md << "The process used " << fixed(cpu / total, 2) << " of the " << threads << " hardware threads on average."
           << serialText << " The largest stages: " << big[0].second << " (" << fixed(100 * big[0].first / total, 0)
           << "%), " << big[1].second << " (" << fixed(100 * big[1].first / total, 0) << "%).\n\n";
    } else {
        md << "The process used " << fixed(cpu / total, 2) << " of the " << threads
           << " hardware threads on average (the machine was shared), so on an idle machine the wall time would lie "
              "between "
           << fixed(idle, 2) << " s ("
           << (serialCpu > 0 ? "the parallel CPU work spread over " + std::to_string(threads) +
                                   " cores, the serial stages named below on one"
                             : "all CPU work spread over " + std::to_string(threads) + " cores")
           << ") and the measured " << fixed(total, 2) << " s; "
           << (idle <= target
                   ? "so this run neither shows the target met nor rules it out for an idle machine."
                   : "even that lower bound misses the target, so it would not be met on an idle 2-core machine "
                     "either (unless the CPU time itself shrinks there: contention also costs cache).")
           << serialText << " The largest stages: " << big[0].second << " (" << fixed(100 * big[0].first / total, 0)
           << "%), " << big[1].second << " (" << fixed(100 * big[1].first / total, 0) << "%), " << big[2].second << " ("
           << fixed(100 * big[2].first / total, 0) << "%).\n\n";
    }
    if (j.contains("materialized")) {
        const json& m = j["materialized"];
        md << "For comparison, the same plies held in memory (`buildPlies = true`: what OBJ, PLY, BCC, pbrt and tube "
              "exports need) cost "
           << fixed(m["plies_seconds"].get<double>(), 2) << " s for `makePlies` plus "
           << fixed(m["export_seconds"].get<double>(), 2) << " s for the GLB of them ("
           << fixed(m["cpu_seconds"].get<double>(), 2) << " s CPU) with a peak of " << gib(m["peak_bytes"]) << " GiB"
           << (m["reset_peak_ok"].get<bool>() ? "" : " (peak not reset: includes the streamed run)")
           << ", on top of the stages before the plies: streaming saves "
           << fixed(m["seconds"].get<double>() - j["stages"].back()["seconds"].get<double>(), 2) << " s and "
           << gib(m["peak_bytes"].get<double>() - j["peak_bytes"].get<double>()) << " GiB here.\n\n";
    }
    rep.summary.push_back({{"setting", "garment: " + fixed(yv / 1e6, 1) + "M yarn vertices to a plies GLB"},
                           {"rule", "target <= 5 s per 10M yarn vertices on 2 cores"},
                           {"knee", "-"},
                           {"default", "-"},
                           {"error", fixed(total, 1) + " s wall, " + gib(j["peak_bytes"]) + " GiB peak: target " +
                                         (total <= target ? "met" : "not met")}});
}

}  // namespace sve
