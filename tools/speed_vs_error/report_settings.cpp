// report_settings.cpp — report sections of the three library settings with a knee: ply resampling
// density (item 1), tube sides (item 2) and Draco position bits (item 3).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "report.hpp"

namespace sve {

// ---- 1 ----
void reportPlies(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    std::ostringstream d;
    d << "# samples_per_turn ns_per_yarn_vertex straight_dev circle_dev ply_vertices_per_yarn_vertex\n";
    for (const json& r : rows)
        d << r["samples_per_turn"] << " " << r["ns_per_yarn_vertex"] << " " << r["straight_max_dev_R"] << " "
          << r["circle_max_dev_R"] << " " << r["ply_vertices_per_yarn_vertex"] << "\n";
    rep.data("plies.dat", d.str());
    const std::vector<double> cost = column(rows, "ply_vertices_per_yarn_vertex"), err = column(rows, "max_dev_R");
    const Knee kn = kneedle(cost, err);
    size_t first = kn.index, last = first;
    // Settings that produce the identical output (the resampler splits each input segment into
    // a whole number of pieces) form one point; the default takes the largest of them.
    while (last + 1 < rows.size() && cost[last + 1] == cost[first] && err[last + 1] == err[first]) ++last;
    const json& k = rows[last];
    const int knee = k["samples_per_turn"], def = defaults["samples_per_turn"];
    size_t next = last + 1;
    while (next < rows.size() && cost[next] == cost[last]) ++next;
    rep.data("plies_knee.dat", std::to_string(k["ns_per_yarn_vertex"].get<double>()) + " " +
                                   std::to_string(k["max_dev_R"].get<double>()) + " " +
                                   std::to_string(k["ply_vertices_per_yarn_vertex"].get<double>()) + "\n");
    rep.multiHeader("samples-per-turn.svg", "Ply resampling density: deviation from the exact helix against vertex "
                                            "count and time (labels: samples per turn)");
    for (int panel = 0; panel < 2; ++panel) {
        const std::string x = panel == 0 ? "5" : "2", kx = panel == 0 ? "3" : "1";
        rep.panel(panel == 0 ? "ply vertices per yarn vertex" : "makePlies time per yarn vertex (ns, best of runs)",
                  "max deviation of the ply polyline (yarn radii)", false, true);
        rep.kneePlot("plies.dat", x, "straight yarn", "circular yarn", "plies_knee.dat", kx);
    }
    rep.endMulti();

    std::ostringstream& md = rep.md;
    md << "## 1. Ply resampling density (`PlyOptions::samplesPerTurn`, `--samples-per-turn`)\n\n"
       << "**Error**: the largest distance from the ply polylines to the exact ply helices, measured at every "
          "vertex and at 7 points inside every segment (so the chord sag between vertices counts); each point's "
          "distance to the analytic helix is found by a golden-section search along the helix. Two yarns whose "
          "plies are known exactly: a straight yarn (12 ply turns) and a circular loop of radius "
       << fixed(j["circle_radius_in_R"], 2) << " R (" << j["circle_turns"].get<double>()
       << " ply turns around it; as tight as "
          "the mapped stockinette's tight bends, whose radius (5% quantile of the circumradius of three consecutive "
          "yarn vertices) is "
       << fixed(j["tight_bend_radius_in_R"], 2)
       << " R, rounded to whole turns), each given at "
          "the vertex spacings the pipeline's own mapped stockinette has (the 5, 25, 50, 75 and 95% quantiles "
          "of its yarn segment lengths: ";
    for (size_t i = 0; i < j["input_spacings_in_R"].size(); ++i)
        md << (i ? ", " : "") << fixed(j["input_spacings_in_R"][i], 2);
    md << " R); the worst over these spacings is reported, because the resampler splits every input segment into "
          "a whole number of pieces and the error of one setting depends on the spacing. So the centripetal "
          "Catmull-Rom resampling, the rotation-minimizing frames and the helix sweep all contribute. "
       << j["plies"].get<int>() << " plies, pitch " << fmt(j["pitch_in_R"]) << " R, ply centre radius "
       << fmt(j["center_radius_in_R"]) << " R (R = yarn radius, the library defaults).\n\n"
       << "**Speed**: `knit::makePlies` on the stockinette mapped onto the drape ("
       << j["speed_scene"]["yarn_vertices"].get<size_t>() << " yarn vertices, "
       << j["speed_scene"]["yarns"].get<size_t>() << " yarns), best of the runs.\n\n"
       << "| samples/turn | ply points per turn (speed scene) | max dev. straight (R) | max dev. circle (R) | ply "
          "vertices | ply vertices per yarn vertex | makePlies (s) | ply vertices/s | ns per yarn vertex |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (size_t i = 0; i < rows.size(); ++i) {
        const json& r = rows[i];
        const int v = r["samples_per_turn"];
        md << "| " << v << marks(i >= first && i <= last, v == def) << " | " << fixed(r["ply_points_per_turn"], 1)
           << " | " << fmt(r["straight_max_dev_R"]) << " | " << fmt(r["circle_max_dev_R"]) << " | "
           << r["ply_vertices"].get<size_t>() << " | " << fixed(r["ply_vertices_per_yarn_vertex"], 2) << " | "
           << fmt(r["seconds"]["best"]) << " | " << fmt(r["ply_vertices_per_second"].get<double>() / 1e6) << " M | "
           << fixed(r["ns_per_yarn_vertex"], 0) << " |\n";
    }
    md << "\n" << rep.image("samples-per-turn.svg", "samples per turn: speed against error") << "\n";
    md << "**Knee** (Kneedle: max deviation against ply vertices per yarn vertex, both normalised over the measured "
          "range; the vertex count is the deterministic cost that makePlies time, memory, export size and render "
          "memory all scale with): **"
       << knee << " samples per turn**";
    if (first != last)
        md << " (" << rows[first]["samples_per_turn"] << ".." << knee
           << " give identical plies at this input spacing, because the resampler splits each input segment into a "
              "whole number of pieces; the default takes the largest, which guarantees at least "
           << knee << " samples per turn for any input spacing)";
    md << ": max deviation " << fmt(k["max_dev_R"]) << " R at " << fixed(k["ply_vertices_per_yarn_vertex"], 2)
       << " ply vertices per yarn vertex. Kneedle scores (distance below the chord, normalised):";
    for (size_t i = 0; i < rows.size(); ++i)
        md << (i ? ", " : " ") << rows[i]["samples_per_turn"] << ": " << fixed(kn.score[i], 3);
    md << ".";
    if (next < rows.size())
        md << " The next denser setting (" << rows[next]["samples_per_turn"] << ") costs "
           << fixed(cost[next] / cost[last], 2) << "x the vertices for " << fixed(err[last] / err[next], 2)
           << "x less deviation; the next coarser one";
    if (first > 0) {
        size_t prev = first - 1;
        md << " (" << rows[prev]["samples_per_turn"] << ") saves " << fixed(100 * (1 - cost[prev] / cost[last]), 0)
           << "% of the vertices but deviates " << fixed(err[prev] / err[last], 2) << "x more.";
    }
    md << " The straight yarn's deviation keeps falling like the square of the ply segment length; the circular "
          "loop's levels off at "
       << fmt(rows.back()["circle_max_dev_R"])
       << " R: that part is the Catmull-Rom "
          "interpolation of a tight bend given by few input vertices, which no samples-per-turn setting removes.";
    if (std::isfinite(rep.budgetR))
        md << " At the knee the deviation is " << fixed(k["max_dev_R"].get<double>() / rep.budgetR, 2)
           << " times the faceting error of the default " << rep.budgetSides << "-sided ply tube (" << fmt(rep.budgetR)
           << " R, item 2).";
    md << (knee == def
               ? " The library default `PlyOptions::samplesPerTurn` is " + std::to_string(def) + ", at the knee."
               : " The library default `PlyOptions::samplesPerTurn` is " + std::to_string(def) +
                     ": **not at the knee of this run**.")
       << "\n\n";
    rep.summary.push_back({{"setting", "`PlyOptions::samplesPerTurn`"},
                           {"rule", "Kneedle knee (cheapest within 1% of the best score)"},
                           {"knee", knee},
                           {"default", def},
                           {"error", fmt(k["max_dev_R"]) + " R max deviation from the exact helix"}});
}

// ---- 2 ----
void reportTubes(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    const double toR = j["ply_radius_in_yarn_radii"];
    std::ostringstream d;
    d << "# sides export_seconds cylinder_r torus_r MB triangles\n";
    for (const json& r : rows)
        d << r["sides"] << " " << r["export_seconds"]["best"] << " " << r["cylinder_hausdorff_r"] << " "
          << r["torus_hausdorff_r"] << " " << r["bytes"].get<double>() / 1e6 << " " << r["triangles"] << "\n";
    rep.data("tubes.dat", d.str());
    const std::vector<double> cost = column(rows, "triangles"), err = column(rows, "hausdorff_r");
    const Knee kn = kneedle(cost, err);
    const json& k = rows[kn.index];
    const int knee = k["sides"], def = defaults["export_sides"];
    rep.data("tubes_knee.dat", std::to_string(k["export_seconds"]["best"].get<double>()) + " " +
                                   std::to_string(k["hausdorff_r"].get<double>()) + " " +
                                   std::to_string(k["triangles"].get<double>() / 1e6) + "\n");
    rep.multiHeader(
        "tube-sides.svg",
        "Tube sides: Hausdorff distance to the exact tube against triangles and GLB export time (labels: sides)");
    for (int panel = 0; panel < 2; ++panel) {
        const std::string x = panel == 0 ? "($6/1e6)" : "2", kx = panel == 0 ? "3" : "1";
        rep.panel(panel == 0 ? "triangles of the test scene's ply tubes (millions; GLB size is proportional)"
                             : "GLB tube export of the test scene (s, best of runs)",
                  "Hausdorff distance (ply radii)", false, true);
        rep.kneePlot("tubes.dat", x, "cylinder (straight ply)", "torus (bent ply)", "tubes_knee.dat", kx);
    }
    rep.endMulti();
    const json& s = j["scene"];
    std::ostringstream& md = rep.md;
    md << "## 2. Tube sides (`TubeOptions::sides`, `ExportOptions::sides`, `--sides`)\n\n"
       << "**Error**: the symmetric Hausdorff distance between the swept tube (`knit::sweepTubes`) and the exact "
          "swept surface, measured against the analytic surface (not against a finer mesh): a straight ply gives an "
          "exact cylinder (16 ply radii long, sampled at the default ply spacing of "
       << fixed(j["cylinder_step_in_r"], 2) << " r), a circular ply of radius " << fmt(j["torus_rc_in_r"])
       << " r (the curvature radius of a default ply helix; 360 samples, chord error "
       << fmt(j["torus_rc_in_r"].get<double>() * (1 - std::cos(kPi / 360)), 2)
       << " r) gives an exact "
          "torus. Mesh to surface: 45 points per triangle, analytic distance. Surface to mesh: a grid on the exact "
          "surface (257 x 720 and 1440 x 360 points), distance to the triangles with CGAL's AABB tree "
          "(`CGAL::AABB_tree`, closest point). r = ply radius = "
       << fmt(toR) << " R.\n\n"
       << "**Cost**: `knit::exportScene` of the ply tubes to GLB (sweep + write) of the stockinette at its physical "
          "size on a 0.2 m drape ("
       << s["cells"].get<size_t>() << " cells, " << s["ply_vertices"].get<size_t>() << " ply vertices, yarn radius "
       << fmt(s["yarn_radius_m"].get<double>() * 1e3)
       << " mm), best of the runs; triangles, tube vertices and file size of that export.\n\n"
       << "| sides | Hausdorff cylinder (r) | Hausdorff torus (r) | max (R) | triangles | tube vertices | triangles "
          "per ply vertex | GLB (MB) | export (s) |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const json& r : rows)
        md << "| " << r["sides"] << marks(r["sides"].get<int>() == knee, r["sides"].get<int>() == def) << " | "
           << fmt(r["cylinder_hausdorff_r"]) << " | " << fmt(r["torus_hausdorff_r"]) << " | " << fmt(r["hausdorff_R"])
           << " | " << r["triangles"].get<size_t>() << " | " << r["vertices"].get<size_t>() << " | "
           << fixed(r["triangles_per_ply_vertex"], 1) << " | " << mb(r["bytes"]) << " | "
           << fmt(r["export_seconds"]["best"]) << " |\n";
    md << "\n"
       << rep.image("tube-sides.svg", "tube sides: speed against error") << "\n"
       << "**Knee** (Kneedle on Hausdorff distance against triangle count over the measured 4..16 sides, the "
          "cheapest setting scoring within 1% of the best): **"
       << knee << " sides**, " << fmt(k["hausdorff_r"]) << " ply radii (" << fmt(k["hausdorff_R"])
       << " yarn radii). Kneedle scores:";
    for (size_t i = 0; i < rows.size(); ++i)
        md << (i ? ", " : " ") << rows[i]["sides"] << ": " << fixed(kn.score[i], 3);
    md << ". "
       << "The faceting error falls like 1 - cos(pi/sides) (the measured values match it) while triangles, vertices, "
          "bytes and export time grow linearly with the sides; both directions of the Hausdorff distance agree (the "
          "rings lie on the surface, the largest gap is at the face centres). ";
    md << (knee == def ? "The library defaults (`TubeOptions::sides`, `ExportOptions::sides`, "
                         "`RenderOptions::tubeSides`) are " +
                             std::to_string(def) + ", at the knee."
                       : "The library default (`ExportOptions::sides`) is " + std::to_string(def) +
                             ": **not at the knee of this run**.")
       << " This faceting error of the default tube is the error budget the other settings are held to below.\n\n";
    rep.summary.push_back(
        {{"setting", "`TubeOptions::sides`, `ExportOptions::sides`"},
         {"rule", "Kneedle knee (cheapest within 1% of the best score)"},
         {"knee", knee},
         {"default", def},
         {"error", fmt(k["hausdorff_r"]) + " r = " + fmt(k["hausdorff_R"]) + " R Hausdorff to the exact tube"}});
}

// ---- 3 ----
void reportDraco(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    std::ostringstream d;
    d << "# bits MB max_error_R bound_R decode_s export_s\n";
    for (const json& r : rows)
        d << r["bits"] << " " << r["bytes"].get<double>() / 1e6 << " " << r["max_error_R"] << " " << r["bound_R"] << " "
          << r["decode_seconds"] << " " << r["export_seconds"]["best"] << "\n";
    rep.data("draco.dat", d.str());
    const bool haveBudget = std::isfinite(rep.budgetR);
    const double tolerance = haveBudget ? 0.5 * rep.budgetR : 0.02;
    double perStep = 0;  // measured error in quantization steps (the worst over the settings)
    for (const json& r : rows) perStep = std::max(perStep, r["max_error_R"].get<double>() / r["step_R"].get<double>());
    const double extent = rows[0]["max_chunk_extent_R"];
    int hereBits = -1;
    for (const json& r : rows)
        if (hereBits < 0 && r["max_error_R"].get<double>() <= tolerance) hereBits = r["bits"];
    auto bitsFor = [&](double extentR) { return int(std::ceil(std::log2(perStep * extentR / tolerance + 1.0))); };
    const double refExtent = 1000.0;
    const int chosen = bitsFor(refExtent), def = defaults["draco_bits"];
    rep.multiHeader("draco-bits.svg",
                    "Draco position bits: max position error against file size and time (labels: bits)");
    rep.panel("GLB size with KHR\\\\_draco\\\\_mesh\\\\_compression (MB)", "max position error (yarn radii)", false,
              true, "top right");
    rep.gp << "plot " << rep.dat("draco.dat")
           << " using 2:3 with linespoints pt 7 title 'measured (decoded file)', \\\n  " << rep.dat("draco.dat")
           << " using 2:4 with lines dt 2 title 'bound: half a step per axis', \\\n  " << rep.dat("draco.dat")
           << " using 2:3:1 with labels offset 1.5,0.7 notitle, \\\n  " << tolerance
           << " with lines lc rgb 'red' dt 3 title 'tolerance: half the default tube faceting'\n";
    rep.panel("seconds (best of runs)", "max position error (yarn radii)", false, true, "top center");
    rep.gp << "plot " << rep.dat("draco.dat")
           << " using 6:3 with linespoints pt 7 title 'exportScene (sweep + encode + write)', \\\n  "
           << rep.dat("draco.dat") << " using 5:3 with linespoints pt 5 title 'decode all primitives', \\\n  "
           << rep.dat("draco.dat") << " using 6:3:1 with labels offset 1.5,0.7 notitle\n";
    rep.endMulti();
    const json& s = j["scene"];
    std::ostringstream& md = rep.md;
    md << "## 3. Draco position quantization (`ExportOptions::dracoBits`, `--draco-bits`)\n\n"
       << "**Error**: the ply tubes (" << j["sides"] << " sides, " << j["tube_vertices"].get<size_t>()
       << " tube vertices) of the stockinette at its physical size on a 0.1 m drape (yarn radius "
       << fmt(s["yarn_radius_m"].get<double>() * 1e3)
       << " mm) are written once as plain float32 GLB and once per "
          "setting with `--draco`. Both files are read back; every Draco primitive is decoded with the Draco decoder "
          "(`draco::Decoder`), node translations are applied, and each decoded vertex (every n-th, about 200k) is "
          "matched to its original (the nearest plain vertex whose normal agrees within 0.05). Reported: the largest "
          "distance in yarn radii, next to the bound of half a quantization step per axis. Draco quantizes each chunk "
          "over its largest axis extent (here up to "
       << fixed(extent, 0) << " R), so the error scales with the chunk extent measured in yarn radii.\n\n"
       << "**Cost**: file size (plain GLB: " << mb(j["plain_bytes"])
       << " MB), `exportScene` time (sweep + encode + "
          "write; the plain export took "
       << fmt(j["plain_export_seconds"])
       << " s) and the time to decode every "
          "primitive of the written file.\n\n"
       << "| bits | max error (R) | bound (R) | GLB (MB) | plain / Draco size | export (s) | decode (s) | decode (M "
          "vertices/s) | vertices checked | unmatched |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const json& r : rows)
        md << "| " << r["bits"] << marks(r["bits"].get<int>() == chosen, r["bits"].get<int>() == def) << " | "
           << fmt(r["max_error_R"]) << " | " << fmt(r["bound_R"]) << " | " << mb(r["bytes"]) << " | "
           << fixed(r["ratio_vs_plain"], 1) << " | " << fmt(r["export_seconds"]["best"]) << " | "
           << fmt(r["decode_seconds"]) << " | "
           << fixed(r["decoded_vertices"].get<double>() / r["decode_seconds"].get<double>() / 1e6, 2) << " | "
           << r["checked_vertices"].get<size_t>() << " | " << r["unmatched_vertices"].get<size_t>() << " |\n";
    md << "\n" << rep.image("draco-bits.svg", "Draco bits: size against error") << "\n";
    md << "**Knee.** The error halves with every bit while the file grows by a few percent per bit (and the "
          "coarsest settings are not even smaller), so on normalised axes the curve has no knee of its own: it "
          "flattens only against the error the geometry already has. ";
    if (haveBudget)
        md << "The rule: the fewest bits whose quantization error is at most half the faceting error of the default "
           << rep.budgetSides << "-sided tube (" << fmt(rep.budgetR) << " R, item 2), i.e. tolerance " << fmt(tolerance)
           << " R; from there on more bits change the geometry's total error by less than half. ";
    else md << "Item 2 was not measured in this run, so the tolerance is 0.02 R. ";
    md << "For this test's chunk extent that is **"
       << (hereBits > 0 ? std::to_string(hereBits) + " bits" : std::string("more than the measured 16 bits"))
       << "**. The measured error is at most " << fixed(perStep, 2)
       << " quantization steps, so a chunk of extent E "
          "(in yarn radii) needs ceil(log2("
       << fixed(perStep, 2) << " E / " << fmt(tolerance) << " + 1)) bits:\n\n"
       << "| chunk extent (yarn radii) | example | bits needed |\n|---:|---|---:|\n";
    const std::vector<std::pair<double, std::string>> examples = {
        {extent, "this test"},
        {500, "0.5 m garment, 1 mm yarn radius"},
        {1000, "1 m garment, 1 mm yarn radius; 0.5 m garment, 0.5 mm"},
        {2000, "1 m garment, 0.5 mm yarn radius"},
        {4000, "2 m sheet, 0.5 mm yarn radius"}};
    for (const auto& [e, what] : examples) md << "| " << fixed(e, 0) << " | " << what << " | " << bitsFor(e) << " |\n";
    const std::vector<double> exportT = column(rows, "export_seconds"), decodeT = column(rows, "decode_seconds");
    const double perBit =
        100.0 * (rows.back()["bytes"].get<double>() / rows[rows.size() - 2]["bytes"].get<double>() - 1.0);
    md << "\nA chunk spans whole yarn courses, so its extent is about the garment's width. The default is chosen for "
          "garments up to "
       << fixed(refExtent, 0) << " yarn radii across: **" << chosen << " bits**. "
       << (chosen == def ? "The library default `ExportOptions::dracoBits` is " + std::to_string(def) + ", matching."
                         : "The library default `ExportOptions::dracoBits` is " + std::to_string(def) +
                               ": **it does not match this run**.")
       << " Larger garments or finer yarn should pass `--draco-bits` from the table; the last bit measured here added "
       << fixed(perBit, 0) << "% to the file; across all settings the export took "
       << fmt(*std::min_element(exportT.begin(), exportT.end())) << " to "
       << fmt(*std::max_element(exportT.begin(), exportT.end())) << " s and decoding "
       << fmt(*std::min_element(decodeT.begin(), decodeT.end())) << " to "
       << fmt(*std::max_element(decodeT.begin(), decodeT.end())) << " s.\n\n";
    rep.summary.push_back({{"setting", "`ExportOptions::dracoBits`"},
                           {"rule", "error <= half the default tube's faceting, chunks up to 1000 R"},
                           {"knee", chosen},
                           {"default", def},
                           {"error", "<= " + fmt(tolerance) + " R position error"}});
}

}  // namespace sve
