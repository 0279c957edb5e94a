// `knit render`: build the scene, render it, write the report, print the report on stdout.
#include "render_command.hpp"

#include <cstdio>
#include <functional>

#include <nlohmann/json.hpp>

#include "bind_command.hpp"
#include "knit/animation.hpp"
#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/output_transaction.hpp"
#include "path_collisions.hpp"
#include "render_flags.hpp"
#include "render_report.hpp"
#include "report.hpp"

namespace knit::cli {
namespace {

// The render's images, then its report, staged in `outputs` and committed together; the report
// is printed on stdout. The fields `extra` gives for the result (e.g. "surface") are added to it.
int finishRender(const RenderCommand& r, OutputTransaction& outputs, const std::function<RenderResult()>& render,
                 const std::function<nlohmann::json(const RenderResult&)>& extra) {
    RenderResult result = outputs.run(render);
    for (std::string& path : result.written) path = outputs.finalNames(path);
    nlohmann::json report = renderReport(result);
    report["camera"] = cameraJson(result.view);
    const nlohmann::json more = extra(result);  // held: items() refers to it
    for (const auto& [key, value] : more.items()) report[key] = value;
    if (!r.report.empty()) outputs.run([&] { writeReport(outputs.stage(r.report), report); });
    outputs.run([&] { outputs.commit(); });
    if (!r.scene.quiet) std::printf("%s\n", report.dump().c_str());  // -q: only errors and warnings
    return 0;
}

// --surface-only: the pattern baked with the render's material, the base mesh traced with it.
int runSurfaceRender(const RenderCommand& r, const SceneOptions& sceneOptions, RenderOptions options,
                     OutputTransaction& outputs) {
    const SurfaceBuild s = bakeSurfaceLevel(sceneOptions, r.surface, resolveMaterial(options));
    const Scene scene = surfaceScene(s);
    options.surface = &s.bake;
    options.surfaceRepeats[0] = s.placement.repeats.x, options.surfaceRepeats[1] = s.placement.repeats.y;
    return finishRender(
        r, outputs, [&] { return renderScene(scene, options); },
        [&](const RenderResult&) {
            return nlohmann::json{{"surface", surfaceReport(s)}};
        });
}

// --bound: the bound scene evaluated on --frame-mesh (or its rest pose) through the Animator, as
// `knit animate` evaluates that frame, at full detail.
Scene boundFrameScene(const RenderCommand& r, const MemoryBudget& budget) {
    if (r.command != nullptr) {
        refuseSceneFlagsWithBound(*r.command);
        if (r.command->count("--detail") > 0 && r.view.detail == Detail::View)
            throw Error("--detail view cannot be given with --bound: a bound scene renders at full detail");
    }
    if (r.surface.surfaceOnly) throw Error("--surface-only cannot be given with --bound");
    const BoundScene bound = readBoundScene(r.bound, budget);
    const Scene& rest = bound.scene;
    BaseMesh mesh = rest.mesh();
    if (!r.frameMesh.empty()) {
        MeshLoadOptions load;
        load.budget = budget;
        mesh = loadMesh(r.frameMesh, load);
        checkFrame(rest.mesh(), mesh, "--frame-mesh '" + r.frameMesh + "'");
    }
    AnimatorOptions ao;
    ao.stats = false;
    ao.radial = true;  // the renderer derives the ply phase from it
    ao.budget = budget;
    const Animator animator(rest, ao);
    AnimationFrame frame;
    animator.evaluate(mesh.positions, frame);
    SceneParts parts;
    parts.mesh = std::move(mesh);
    parts.normals = std::move(frame.meshNormals);
    parts.yarnRadius = rest.yarnRadius();
    parts.grid = rest.grid();
    parts.binding = rest.binding();
    parts.yarns = std::move(frame.yarns);
    if (parts.yarns.colour.empty()) parts.yarns.colour = rest.yarns().colour;
    parts.plies = std::move(frame.plies);
    parts.plyOptions = animator.plyOptions();
    parts.pattern = rest.pattern();
    parts.placement = rest.placement();
    parts.bindStats = rest.bindStats();
    return Scene::fromParts(std::move(parts));
}

}  // namespace

void addRenderCommand(CLI::App& app, RenderCommand& r) {
    r.command = app.add_subcommand("render", "Path-trace the knit on its base mesh (front- or back-lit)");
    addSceneFlags(*r.command, r.scene);
    addRenderFlags(*r.command, r.options);
    addViewFlags(*r.command, r.view, r.options.fovDegrees, r.options.width, r.options.height, Detail::View);
    r.command->add_option("--report", r.report, "Write a JSON report (time, rays/s, memory)");
    addSurfaceFlags(*r.command, r.surface, true);
    r.command->add_option("--bound", r.bound,
                          "Bound scene file (`knit bind`): render it at full detail without binding (no scene flags "
                          "besides --max-memory and -q)");
    r.command->add_option(
        "--frame-mesh", r.frameMesh,
        "With --bound: the pose to render (a mesh with the rest mesh's connectivity; default the rest "
        "pose), evaluated as `knit animate` evaluates that frame");
    r.command->footer(kSceneHelp);
}

int runRender(const RenderCommand& r) {
    checkReportPath(r.report);  // before the scene and the render: the same check as `build`
    refuseCollidingPaths({{"--mesh", r.scene.scene.mesh},
                          {"--pattern", r.scene.scene.pattern},
                          {"--material", r.options.materialFile},
                          {"--bound", r.bound},
                          {"--frame-mesh", r.frameMesh}},
                         {{"--output", r.options.output}, {"--exr", r.options.exr}, {"--report", r.report}});
    // Step 1: the camera (validated before any work); the PNG, the EXR and the report are staged
    // and committed together at the end.
    OutputTransaction outputs;
    RenderOptions options = r.options;
    options.progress = options.progress && !r.scene.quiet;
    const ImageSize image{options.fovDegrees, options.width, options.height};
    options.view = givenView(r.view, image);
    options.output = outputs.stage(r.options.output);
    options.exr = outputs.stage(r.options.exr);
    SceneFlags flags = r.scene;
    // A bound scene file carries its deformation (and strain table): nothing is decided here.
    if (!r.bound.empty()) flags.deform = "none";
    SceneOptions sceneOptions = resolveScene(flags);
    options.budget = sceneOptions.budget;  // --max-memory
    // The surface level of --detail view: --bake-size when given, else the width the view needs.
    options.viewBakeSize = r.surface.bakeSizeGiven() ? r.surface.bakeSize : 0;
    options.surfaceScatteringPaths = r.surface.scatteringPaths;
    if (!r.bound.empty()) {  // a bound scene (`knit bind`), posed, at full detail
        const Scene scene = boundFrameScene(r, sceneOptions.budget);
        return finishRender(
            r, outputs, [&] { return renderScene(scene, options); },
            [&](const RenderResult& result) {
                return nlohmann::json{{"levels", levelsJson(levelStats(scene), result.surfaceTextured)}};
            });
    }
    if (!r.frameMesh.empty()) throw Error("--frame-mesh needs --bound");
    if (r.surface.surfaceOnly) return runSurfaceRender(r, sceneOptions, options, outputs);
    // Step 2: the detail the view asks for, the scene, the render and the report (with the levels).
    sceneOptions.detail = detailOptions(r.view, image, options.light == LightPlacement::Back, /*yarnCurves=*/true);
    const Scene scene = buildScene(sceneOptions);
    printWarnings(scene);
    return finishRender(
        r, outputs, [&] { return renderScene(scene, options); },
        [&](const RenderResult& result) {
            return nlohmann::json{{"levels", levelsJson(levelStats(scene), result.surfaceTextured)}};
        });
}

}  // namespace knit::cli
