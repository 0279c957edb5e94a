// knit — command-line front end. It only composes library stages (knit/scene.hpp) with the
// exporters (knit/export.hpp) and, when built, the render check (knit/render.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/scene.hpp"
#ifdef KNIT_HAVE_RENDER_CHECK
#include "knit/render.hpp"
#endif

namespace {

struct SceneFlags {
    knit::SceneOptions scene;
    std::vector<double> repeats;
    std::string twist = "S";
    int meshRes = 0;
    bool noWeld = false;
    bool quiet = false;
};

const char* kSceneHelp = R"(Scene: a pattern (.pyp file, .json curves file, or built-in name) tiled over a
base mesh (.obj/.ply/.off/.gltf/.glb with UVs, or built-in name). Alignment: with --repeats U V, pattern
point (x, y) of tile (i, j) lands at uv ((x + i px)/(U px), (y + j py)/(V py)); the pattern's
origin is uv (0,0). Heights and radii scale with the period. Without --repeats the pattern keeps
its physical size (the mesh's area-weighted metres per UV unit).)";

void addSceneFlags(CLI::App* cmd, SceneFlags& f) {
    std::string patterns, meshes;
    for (const auto& n : knit::builtinPatternNames()) patterns += (patterns.empty() ? "" : ", ") + n;
    for (const auto& n : knit::builtinMeshNames()) meshes += (meshes.empty() ? "" : ", ") + n;
    cmd->add_option("--pattern", f.scene.pattern, "Pattern file (.pyp, .json curves) or built-in: " + patterns)->capture_default_str();
    cmd->add_option("--mesh", f.scene.mesh, "Base mesh file (.obj, .ply, .off, .gltf, .glb; needs UVs; glTF v is flipped to OBJ convention) or built-in: " + meshes)->capture_default_str();
    cmd->add_option("--repeats", f.repeats, "Pattern periods across u in [0,1] and v in [0,1] (default: physical size)")->expected(2);
    cmd->add_option("--mesh-res", f.meshRes, "Quads per side of built-in meshes (default 32)")->check(CLI::Range(1, 4096));
    cmd->add_option("--plies", f.scene.plies.count, "Plies per yarn")->capture_default_str()->check(CLI::Range(1, 16));
    cmd->add_option("--ply-pitch", f.scene.plies.pitch, "Length of one ply turn in metres (0: 6 yarn radii)")->capture_default_str();
    cmd->add_option("--ply-radius", f.scene.plies.plyRadius, "Ply radius in metres (0: touching plies filling the yarn)")->capture_default_str();
    cmd->add_option("--ply-center-radius", f.scene.plies.centerRadius, "Distance of ply centres from the yarn centre (0: auto)")->capture_default_str();
    cmd->add_option("--twist", f.twist, "Ply twist direction")->check(CLI::IsMember({"S", "Z"}))->capture_default_str();
    cmd->add_option("--samples-per-turn", f.scene.plies.samplesPerTurn, "Centreline samples per ply turn")->capture_default_str();
    cmd->add_option("--clamp-tolerance", f.scene.bind.clampTolerance,
                    "Points outside the UV region within this many yarn radii are clamped onto the closest triangle; farther ones are cut")->capture_default_str();
    cmd->add_option("--weld-tolerance", f.scene.bind.weldTolerance,
                    "Cut ends meeting again across a seam within this many yarn radii are welded")->capture_default_str();
    cmd->add_flag("--no-weld", f.noWeld, "Do not weld yarn ends across UV seams");
    cmd->add_flag("-q,--quiet", f.quiet, "No progress output on stderr");
}

knit::SceneOptions resolveScene(SceneFlags& f) {
    knit::SceneOptions o = f.scene;
    if (!f.repeats.empty()) o.placement.repeats = {f.repeats[0], f.repeats[1]};
    if (f.meshRes > 0) o.meshOptions.resU = o.meshOptions.resV = f.meshRes;
    o.plies.twist = f.twist == "Z" ? knit::Twist::Z : knit::Twist::S;
    o.bind.weld = !f.noWeld;
    if (!f.quiet)
        o.progress = [](const std::string& stage, int index, int total) {
            std::fprintf(stderr, "[%d/%d] %s\n", index + 1, total, stage.c_str());
        };
    return o;
}

// Writes the JSON report atomically.
void writeReport(const std::string& path, const nlohmann::json& report) {
    knit::writeFileAtomically(path, [&](std::ostream& out) { out << report.dump(2) << '\n'; }, false);
}

// What the user should know about a built scene that is not an error (stderr).
void printWarnings(const knit::Scene& s) {
    if (s.grid.overlappingCharts.empty()) return;
    std::string pairs;
    const size_t shown = std::min<size_t>(s.grid.overlappingCharts.size(), 8);
    for (size_t k = 0; k < shown; ++k)
        pairs += (pairs.empty() ? "" : ", ") + std::to_string(s.grid.overlappingCharts[k].x) + "/" +
                 std::to_string(s.grid.overlappingCharts[k].y);
    if (shown < s.grid.overlappingCharts.size())
        pairs += " and " + std::to_string(s.grid.overlappingCharts.size() - shown) + " more pairs";
    std::fprintf(stderr, "knit: note: %s: UV charts overlap (%s); each chart is tiled and knitted on its own\n",
                 s.mesh.name.c_str(), pairs.c_str());
}

// The scene report plus the export; streamed plies are counted by the export.
nlohmann::json buildReportJson(const knit::Scene& scene, const knit::ExportStats& stats, bool streamed) {
    nlohmann::json report = knit::sceneReport(scene);
    if (streamed) {
        const knit::PlyOptions o = knit::resolvePlyOptions(scene.plyOptions);
        report["vertices"]["ply"] = stats.vertices;
        report["plies"] = {{"curves", stats.curves},
                           {"ply_radius", o.plyRadius},
                           {"center_radius", o.centerRadius},
                           {"pitch", o.pitch},
                           {"streamed", true}};
    }
    report["export"] = knit::exportReport(stats);
    return report;
}

void printSummary(const knit::Scene& s, const knit::ExportStats& e, const std::string& output, bool streamed) {
    const nlohmann::json r = knit::sceneReport(s);
    std::printf("pattern %s on mesh %s: repeats %.4g x %.4g, yarn radius %.4g m\n", s.pattern.name.c_str(), s.mesh.name.c_str(),
                s.placement.repeats.x, s.placement.repeats.y, s.yarnRadius);
    std::printf("%zu cells, %zu yarns (%zu closed loops, %zu open ends, %zu welded ends), %zu yarn vertices, %zu ply vertices\n",
                s.grid.cells.size(), s.yarns.curves.curveCount(), s.bound.stats.closedLoops, s.bound.stats.openEnds,
                s.bound.stats.weldedEnds, s.yarns.curves.pointCount(), streamed ? e.vertices : s.plies.curves.pointCount());
    std::printf("wrote %s (%s, %zu curves, %zu vertices) in %.3f s total\n", output.c_str(), e.format.c_str(), e.curves, e.vertices,
                r["seconds"]["total"].get<double>() + e.seconds);
}

int runInfo(const std::string& what, bool json) {
    const knit::Pattern p = knit::loadPatternFileOrName(what);
    const knit::PatternInfo info = knit::describePattern(p);
    if (json) {
        nlohmann::json j = {{"name", p.name},
                            {"period", {info.px, info.py}},
                            {"radius", info.radius},
                            {"vertices", info.vertexCount},
                            {"edges", info.edgeCount},
                            {"crossings", {{"+x", info.crossings[0]}, {"-x", info.crossings[1]}, {"+y", info.crossings[2]}, {"-y", info.crossings[3]}}},
                            {"loops_1x1", info.loops1x1},
                            {"open_yarns_1x1", info.openYarns1x1}};
        std::cout << j.dump(2) << '\n';
        return 0;
    }
    std::printf("pattern   %s\n", p.name.c_str());
    std::printf("period    %.9g x %.9g m\n", info.px, info.py);
    std::printf("radius    %.9g m\n", info.radius);
    std::printf("vertices  %zu\nedges     %zu\n", info.vertexCount, info.edgeCount);
    std::printf("crossing  +x %zu, -x %zu, +y %zu, -y %zu\n", info.crossings[0], info.crossings[1], info.crossings[2], info.crossings[3]);
    std::printf("bounds    x [%.6g, %.6g] y [%.6g, %.6g] z [%.6g, %.6g]\n", info.boundsMin.x, info.boundsMax.x, info.boundsMin.y,
                info.boundsMax.y, info.boundsMin.z, info.boundsMax.z);
    std::printf("1x1 periodic tiling: %zu closed loops, %zu open yarns\n", info.loops1x1, info.openYarns1x1);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"knit: ply-level knitted fabric on a UV-mapped triangle mesh (libknit)"};
    app.require_subcommand(1);
    app.footer(kSceneHelp);

    // knit build
    SceneFlags buildFlags;
    knit::ExportOptions exportOptions;
    exportOptions.path = "knit-plies.obj";
    std::string buildReport;
    CLI::App* build = app.add_subcommand("build", "Tile, stitch, map and twist plies; export curves or tubes");
    addSceneFlags(build, buildFlags);
    knit::addExportFlags(*build, exportOptions);
    build->add_option("-o,--output", exportOptions.path, "Output file; the extension picks the format")->capture_default_str();
    build->add_option("--report", buildReport, "Write a JSON report (counts, stage times, segment lengths)");
    build->footer(kSceneHelp);

    // knit info
    std::string infoWhat;
    bool infoJson = false;
    CLI::App* info = app.add_subcommand("info", "Describe a pattern: period, radius, counts, edges crossing each side, loops of a 1x1 tiling");
    info->add_option("pattern", infoWhat, "Pattern file (.pyp / .json) or built-in name")->required();
    info->add_flag("--json", infoJson, "Print JSON");

    // knit generate
    std::string genName = "stockinette", genOutput;
    knit::StockinetteParams stock;
    CLI::App* gen = app.add_subcommand("generate", "Write one of the project's parametric patterns as .pyp");
    gen->add_option("name", genName, "Generator: stockinette")->check(CLI::IsMember({"stockinette"}))->capture_default_str();
    gen->add_option("-o,--output", genOutput, "Output .pyp file")->required();
    gen->add_option("--a", stock.a, "Loop width (model units)")->capture_default_str();
    gen->add_option("--h", stock.h, "Loop height (model units)")->capture_default_str();
    gen->add_option("--d", stock.d, "Over/under depth (model units)")->capture_default_str();
    gen->add_option("--row-gap", stock.rowGap, "Extra row spacing (model units)")->capture_default_str();
    gen->add_option("--model-radius", stock.modelRadius, "Yarn radius (model units)")->capture_default_str();
    gen->add_option("--radius", stock.radius, "Yarn radius (metres)")->capture_default_str();
    gen->add_option("--samples", stock.samplesPerStitch, "Samples per stitch")->capture_default_str();

#ifdef KNIT_HAVE_RENDER_CHECK
    SceneFlags renderFlags;
    knit::RenderOptions renderOptions;
    std::string renderReportPath;
    CLI::App* render = app.add_subcommand("render", "Path-trace the knit on its base mesh (front- or back-lit)");
    addSceneFlags(render, renderFlags);
    knit::addRenderFlags(*render, renderOptions);
    render->add_option("--report", renderReportPath, "Write a JSON report (time, rays/s, memory)");
    render->footer(kSceneHelp);
#endif

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        if (*info) return runInfo(infoWhat, infoJson);
        if (*gen) {
            const knit::Pattern p = knit::generateStockinette(stock);
            knit::writeFileAtomically(genOutput, [&](std::ostream& out) { knit::writePyp(out, p); }, false);
            std::printf("wrote %s (%zu vertices, period %.9g x %.9g m)\n", genOutput.c_str(), p.points.size(), p.px, p.py);
            return 0;
        }
        if (*build) {
            // Fail before the scene is built: bad export options or an unwritable report folder.
            knit::validateExportOptions(exportOptions);
            if (!buildReport.empty()) knit::requireWritableFolder(buildReport, "report");
            knit::SceneOptions options = resolveScene(buildFlags);
            // glTF / GLB ply curves are generated while writing: the scene is built without them.
            const bool streamed = knit::streamsPlies(exportOptions);
            options.buildPlies = exportOptions.what != knit::ExportWhat::Yarns && !streamed;
            const knit::Scene scene = knit::buildScene(options);
            printWarnings(scene);
            const knit::ExportStats stats = knit::exportScene(scene, exportOptions);
            if (!buildReport.empty()) {
                const nlohmann::json report = buildReportJson(scene, stats, streamed);
                try {
                    writeReport(buildReport, report);
                } catch (...) {
                    std::filesystem::remove(exportOptions.path);  // the report is part of the result
                    throw;
                }
            }
            printSummary(scene, stats, exportOptions.path, streamed);
            return 0;
        }
#ifdef KNIT_HAVE_RENDER_CHECK
        if (*render) {
            renderOptions.progress = renderOptions.progress && !renderFlags.quiet;
            const knit::Scene scene = knit::buildScene(resolveScene(renderFlags));
            printWarnings(scene);
            const knit::RenderResult result = knit::renderScene(scene, renderOptions);
            const nlohmann::json report = knit::renderReport(result);
            if (!renderReportPath.empty()) writeReport(renderReportPath, report);
            std::printf("%s\n", report.dump().c_str());
            return 0;
        }
#endif
    } catch (const knit::Error& e) {
        std::fprintf(stderr, "knit: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "knit: internal error: %s\n", e.what());
        return 3;
    }
    return 0;
}
