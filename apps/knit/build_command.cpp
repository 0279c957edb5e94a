// `knit build`: check the outputs, build the scene, export it, write the report, print a summary.
#include "build_command.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "export_flags.hpp"
#include "export_report.hpp"
#include "knit/animation.hpp"
#include "knit/output_transaction.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/surface_export.hpp"
#include "util/platform.hpp"
#include "path_collisions.hpp"
#include "report.hpp"
#include "rest_pose.hpp"

namespace knit::cli {
namespace {

// The camera of the report: the scene's view, else the given one, else the default framing.
View reportView(const Scene& scene, const BuildCommand& b) {
    if (scene.detail()) return scene.detail()->view;
    if (const std::optional<View> given = givenView(b.view, b.view.image)) return *given;
    View settings;
    settings.fovDegrees = b.view.image.fovDegrees, settings.width = b.view.image.width;
    settings.height = b.view.image.height;
    return frameMesh(scene.mesh(), scene.yarnMargin(), settings);
}

// The view's surface level: the base-mesh triangles of its surface-level cells with the pattern
// baked as for --surface-only (null when the view has none). Needs a glTF output.
std::unique_ptr<SurfaceLayer> surfaceLevel(const Scene& built, const SceneOptions& options, const BuildCommand& b) {
    if (!built.detail() || built.detail()->pieces.surfaceFaces.empty()) return nullptr;
    const std::vector<uint32_t>& faces = built.detail()->pieces.surfaceFaces;
    const std::string ext = util::lowerExtension(b.exportOptions.path);
    if (ext != "glb" && ext != "gltf")
        throw Error("-o '" + b.exportOptions.path + "': the view has " + std::to_string(faces.size()) +
                    " base-mesh triangles at the surface level, whose baked knit material needs a .glb or .gltf "
                    "output (or use --detail full)");
#ifdef KNIT_HAVE_RENDER_CHECK
    // The scene's own pattern, placement and ply options: nothing is loaded again.
    auto layer = std::make_unique<SurfaceLayer>();
    layer->images = surfaceImages(bakePattern(built.pattern(), built.placement(), options.plies, b.surface, {}));
    layer->mesh = meshSubset(built.mesh(), faces, " (surface level)");
    layer->material.repeats = built.placement().repeats;
    return layer;
#else
    (void)options;
    throw Error("the view has surface-level cells, but this knit was built without render_check, which bakes their "
                "material; use --detail full");
#endif
}

// The scene report plus the export, the camera and the levels; plies the export generated
// (streamed, or a view's pieces) are counted by the export.
nlohmann::json buildReportJson(const Scene& scene, const SceneStats& numbers, const ExportStats& stats, bool streamed,
                               const View& view, bool surfaceTextured, bool exportMadePlies) {
    nlohmann::json report = sceneReport(scene, numbers);
    LevelStats levels = numbers.levels;
    if (exportMadePlies) levels.plies.plyVertices = stats.vertices, levels.plies.bytes = 16 * stats.vertices;
    report["camera"] = cameraJson(view);
    report["levels"] = levelsJson(levels, surfaceTextured);
    // Files have no yarn-level shading: those cells are written with their plies (viewPiecesScene),
    // counted with the ply level's plyVertices.
    if (scene.detail()) report["levels"]["yarns"]["exportedAs"] = "plies";
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
    std::printf("wrote %s (%s, %zu curves, %zu vertices", output.c_str(), e.format.c_str(), e.curves, e.vertices);
    if (e.surfaceTriangles > 0)
        std::printf("; surface level: %zu triangles with the baked knit material", e.surfaceTriangles);
    std::printf(") in %.3f s total\n", st.totalSeconds + e.seconds);
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
    if (b.view.detail == Detail::View)
        throw Error("--detail view does not apply to --rest (an animation frame is built at full detail)");
    checkOutputs(b);
    const SceneOptions options = resolveScene(b.scene);
    const Scene rest = bindRestPose(options, b.rest);
    printWarnings(rest);
    AnimatorOptions ao;
    ao.budget = options.budget;
    ao.plies = b.exportOptions.what != ExportWhat::Yarns;
    ao.stats = false;
    const Animator animator(rest, ao);
    BaseMesh mesh = loadMesh(options.mesh);
    checkFrame(rest.mesh(), mesh, "--mesh '" + options.mesh + "'");
    AnimationFrame frame;
    animator.evaluate(mesh.positions, frame);
    // The export and the report are committed together: an existing -o stays unchanged if the report fails.
    OutputTransaction outputs;
    const ExportOptions staged = stagedExport(b.exportOptions, options.budget, outputs);
    const ExportStats stats = outputs.run([&] { return exportScene(frameScene(animator, mesh, frame), staged); });
    if (!b.report.empty()) {
        nlohmann::json report = sceneReport(rest, sceneStats(rest));
        report["rest"] = b.rest;
        report["export"] = exportReport(stats);
        outputs.run([&] { writeReport(outputs.stage(b.report), report); });
    }
    outputs.run([&] { outputs.commit(); });
    std::printf("bound on %s, evaluated on %s: wrote %s (%s, %zu curves, %zu vertices)\n", b.rest.c_str(),
                options.mesh.c_str(), b.exportOptions.path.c_str(), stats.format.c_str(), stats.curves, stats.vertices);
    return 0;
}

#ifdef KNIT_HAVE_RENDER_CHECK
// --surface-only: the base mesh with the baked knit material, no yarns or plies.
int runSurfaceOnly(const BuildCommand& b) {
    checkReportPath(b.report);
    const std::string& out = b.exportOptions.path;
    refuseCollidingPaths({{"--mesh", b.scene.scene.mesh}, {"--pattern", b.scene.scene.pattern}},
                         {{"-o", out}, {"--report", b.report}});
    // The GLB and the report are committed together: an existing -o stays unchanged if the report fails.
    OutputTransaction outputs;
    const SurfaceBuild s = outputs.run(
        [&] { return runSurfaceBuild(resolveScene(b.scene), b.surface, PlyMaterial{}, outputs.stage(out)); });
    if (!b.report.empty()) {
        const nlohmann::json report = {{"pattern", s.pattern.name},
                                       {"mesh", s.mesh.name},
                                       {"surface", surfaceReport(s)},
                                       {"export", surfaceExportReport(s)}};
        outputs.run([&] { writeReport(outputs.stage(b.report), report); });
    }
    outputs.run([&] { outputs.commit(); });
    std::printf(
        "baked %s at %d x %d (mean coverage %.3f) in %.3f s; wrote %s (%zu vertices, %zu triangles, %zu bytes)\n",
        s.pattern.name.c_str(), s.bake.width, s.bake.height, s.bake.meanCoverage(), s.bake.seconds, out.c_str(),
        s.exported.vertices, s.exported.triangles, s.exported.bytes);
    return 0;
}
#endif

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
#ifdef KNIT_HAVE_RENDER_CHECK
    addSurfaceFlags(*b.command, b.surface);
#endif
    addViewFlags(*b.command, b.view, b.view.image.fovDegrees, b.view.image.width, b.view.image.height, Detail::Full);
    b.command->footer(kSceneHelp);
}

int runBuild(const BuildCommand& b) {
    if (!b.rest.empty()) return runBuildOnRestPose(b);
#ifdef KNIT_HAVE_RENDER_CHECK
    if (b.surface.surfaceOnly) return runSurfaceOnly(b);
#endif
    // Step 1: fail before the scene is built (options, report folder, colliding paths, camera).
    checkOutputs(b);
    givenView(b.view, b.view.image);  // a bad camera fails here (knit::Error naming the option)
#ifdef KNIT_HAVE_RENDER_CHECK
    requireBakeSize(b.surface);  // a view's surface level is baked after the scene is built
#endif
    // Step 2: the scene; glTF / GLB ply curves are generated while writing, so it is built without them.
    SceneOptions options = resolveScene(b.scene);
    const bool streamed = streamsPlies(b.exportOptions);
    options.buildPlies = b.exportOptions.what != ExportWhat::Yarns && !streamed;
    options.detail = detailOptions(b.view, b.view.image, false, true);
    if (options.detail) options.buildPlies = false;  // the export generates the plies of the pieces it writes
    const Scene built = buildScene(options);
    // A view's pieces are exported as curves (knit/scene.hpp viewPiecesScene).
    const Scene scene = built.detail() ? viewPiecesScene(built, b.exportOptions.what != ExportWhat::Yarns) : Scene();
    const Scene& exported = built.detail() ? scene : built;
    printWarnings(built);
    const std::unique_ptr<SurfaceLayer> surface = surfaceLevel(built, options, b);
    if (built.detail() && !surface && exported.yarns().curves.curveCount() == 0)
        throw Error(
            "the view sees none of the cloth (every cell is culled): check --eye and --target; no file written");
    // Before the outputs are staged, so a refusal names -o (exportScene checks the staged path again).
    checkSceneExport(exported, b.exportOptions, surface.get());
    // Step 3: the export, then the report, staged and committed together: an existing -o (or report)
    // stays unchanged unless both are complete.
    OutputTransaction outputs;
    const ExportOptions staged = stagedExport(b.exportOptions, options.budget, outputs);
    const ExportStats stats = outputs.run([&] { return exportScene(exported, staged, surface.get()); });
    const SceneStats sceneNumbers = sceneStats(built);  // counts, segment lengths, stage times
    if (!b.report.empty()) {
        nlohmann::json report =
            buildReportJson(built, sceneNumbers, stats, streamed, reportView(built, b), surface != nullptr,
                            streamed || (built.detail() && b.exportOptions.what != ExportWhat::Yarns));
        if (surface) {
            report["export"]["surface"]["bakeWidth"] = surface->images.width;
            report["export"]["surface"]["bakeHeight"] = surface->images.height;
        }
        outputs.run([&] { writeReport(outputs.stage(b.report), report); });
    }
    outputs.run([&] { outputs.commit(); });
    // Step 4: the summary on stdout (none with -q: only errors and warnings then).
    if (!b.scene.quiet) printSummary(built, sceneNumbers, stats, b.exportOptions.path, streamed);
    return 0;
}

}  // namespace knit::cli
