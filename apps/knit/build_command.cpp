// `knit build`: check the outputs, build the scene, export it, write the report, print a summary.
#include "build_command.hpp"

#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "empty_result.hpp"
#include "export_flags.hpp"
#include "export_report.hpp"
#include "knit/animation.hpp"
#include "float_range.hpp"
#include "path_collisions.hpp"
#include "report.hpp"
#include "rest_pose.hpp"

namespace knit::cli {
namespace {

// The scene report plus the export; streamed plies are counted by the export.
nlohmann::json buildReportJson(const Scene& scene, const SceneStats& numbers, const ExportStats& stats, bool streamed) {
    nlohmann::json report = sceneReport(scene, numbers);
    if (streamed) {
        const PlyOptions o = resolvePlyOptions(scene.plyOptions());
        report["vertices"]["ply"] = stats.vertices;
        report["plies"] = {{"curves", stats.curves},
                           {"ply_radius", o.plyRadius},
                           {"center_radius", o.centerRadius},
                           {"pitch", o.pitch},
                           {"streamed", true}};
    }
    report["export"] = exportReport(stats);
    return report;
}

void printSummary(const Scene& s, const SceneStats& st, const ExportStats& e, const std::string& output,
                  bool streamed) {
    std::printf("pattern %s on mesh %s: repeats %.4g x %.4g, yarn radius %.4g m\n", s.pattern().name.c_str(),
                s.mesh().name.c_str(), s.placement().repeats.x, s.placement().repeats.y, s.yarnRadius());
    std::printf("%zu cells, %zu yarns (%zu closed loops, %zu open ends, %zu welded ends), %zu yarn vertices, %zu ply "
                "vertices\n",
                st.cells, st.yarns, st.bind.closedLoops, st.bind.openEnds, st.bind.weldedEnds, st.yarnVertices,
                streamed ? e.vertices : st.plyVertices);
    std::printf("wrote %s (%s, %zu curves, %zu vertices) in %.3f s total\n", output.c_str(), e.format.c_str(), e.curves,
                e.vertices, st.totalSeconds + e.seconds);
}

// Fails before any scene is built: bad export options, an unwritable report folder, or an output
// that is one of the inputs (--mesh, --pattern, --rest) or another output.
void checkOutputs(const BuildCommand& b) {
    validateExportOptions(b.exportOptions);
    checkReportPath(b.report);
    const std::string& out = b.exportOptions.path;
    refuseCollidingPaths({{"--mesh", b.scene.scene.mesh}, {"--pattern", b.scene.scene.pattern}, {"--rest", b.rest}},
                         {{"-o", out}, {"the glTF buffer of -o", gltfBufferOf(out)}, {"--report", b.report}});
}

// --rest: bound on the rest mesh, evaluated on --mesh (what `knit animate` writes for that frame).
int runBuildOnRestPose(const BuildCommand& b) {
    checkOutputs(b);
    const SceneOptions options = resolveScene(b.scene);
    const Scene rest = bindRestPose(options, b.rest);
    printWarnings(rest);
    AnimatorOptions ao;
    ao.plies = b.exportOptions.what != ExportWhat::Yarns;
    ao.stats = false;
    const Animator animator(rest, ao);
    BaseMesh mesh = loadMesh(options.mesh);
    checkFrame(rest.mesh(), mesh, "--mesh '" + options.mesh + "'");
    AnimationFrame frame;
    animator.evaluate(mesh.positions, frame);
    const ExportStats stats = exportScene(frameScene(animator, mesh, frame), b.exportOptions);
    if (!b.report.empty()) {
        nlohmann::json report = sceneReport(rest, sceneStats(rest));
        report["rest"] = b.rest;
        report["export"] = exportReport(stats);
        try {
            writeReport(b.report, report);
        } catch (...) {
            std::filesystem::remove(b.exportOptions.path);
            throw;
        }
    }
    std::printf("bound on %s, evaluated on %s: wrote %s (%s, %zu curves, %zu vertices)\n", b.rest.c_str(),
                options.mesh.c_str(), b.exportOptions.path.c_str(), stats.format.c_str(), stats.curves, stats.vertices);
    return 0;
}

}  // namespace

void addBuildCommand(CLI::App& app, BuildCommand& b) {
    b.exportOptions.path = "knit-plies.obj";
    b.command = app.add_subcommand("build", "Tile, stitch, map and twist plies; export curves or tubes");
    addSceneFlags(*b.command, b.scene);
    addExportFlags(*b.command, b.exportOptions);
    b.command->add_option("-o,--output", b.exportOptions.path, "Output file; the extension picks the format")
        ->capture_default_str();
    b.command->add_option("--report", b.report, "Write a JSON report (counts, stage times, segment lengths)");
    b.command->add_option(
        "--rest", b.rest,
        "Bind on this rest-pose mesh and evaluate on --mesh (same connectivity): one frame of `knit animate`");
    b.command->footer(kSceneHelp);
}

int runBuild(const BuildCommand& b) {
    if (!b.rest.empty()) return runBuildOnRestPose(b);
    // Step 1: fail before the scene is built (options, report folder, colliding paths).
    checkOutputs(b);
    // Step 2: the scene; glTF / GLB ply curves are generated while writing, so it is built without them.
    SceneOptions options = resolveScene(b.scene);
    const bool streamed = streamsPlies(b.exportOptions);
    options.buildPlies = b.exportOptions.what != ExportWhat::Yarns && !streamed;
    const Scene scene = buildScene(options);
    printWarnings(scene);
    refuseValuesBeyondFloat32(scene, b.exportOptions);
    refuseEmptyExport(scene, b.exportOptions);
    // Step 3: the export, then the report (part of the result: without it the export is removed).
    const ExportStats stats = exportScene(scene, b.exportOptions);
    const SceneStats sceneNumbers = sceneStats(scene);  // counts, segment lengths, stage times
    if (!b.report.empty()) {
        const nlohmann::json report = buildReportJson(scene, sceneNumbers, stats, streamed);
        try {
            writeReport(b.report, report);
        } catch (...) {
            std::filesystem::remove(b.exportOptions.path);
            throw;
        }
    }
    // Step 4: the summary on stdout.
    printSummary(scene, sceneNumbers, stats, b.exportOptions.path, streamed);
    return 0;
}

}  // namespace knit::cli
