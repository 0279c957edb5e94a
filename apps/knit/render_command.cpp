// `knit render`: build the scene, render it, write the report, print the report on stdout.
#include "render_command.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "path_collisions.hpp"
#include "render_flags.hpp"
#include "render_report.hpp"
#include "report.hpp"

namespace knit::cli {
namespace {

// --surface-only: the pattern baked with the render's material, the base mesh traced with it.
int runSurfaceRender(const RenderCommand& r, RenderOptions options) {
    const SurfaceBuild s = bakeSurfaceLevel(resolveScene(r.scene), r.surface, resolveMaterial(options));
    const Scene scene = surfaceScene(s);
    options.surface = &s.bake;
    options.surfaceRepeats[0] = s.placement.repeats.x, options.surfaceRepeats[1] = s.placement.repeats.y;
    nlohmann::json report = renderReport(renderScene(scene, options));
    report["surface"] = surfaceReport(s);
    if (!r.report.empty()) writeReport(r.report, report);
    std::printf("%s\n", report.dump().c_str());
    return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, RenderCommand& r) {
    r.command = app.add_subcommand("render", "Path-trace the knit on its base mesh (front- or back-lit)");
    addSceneFlags(*r.command, r.scene);
    addRenderFlags(*r.command, r.options);
    r.command->add_option("--report", r.report, "Write a JSON report (time, rays/s, memory)");
    addSurfaceFlags(*r.command, r.surface);
    r.command->footer(kSceneHelp);
}

int runRender(const RenderCommand& r) {
    checkReportPath(r.report);  // before the scene and the render: the same check as `build`
    refuseCollidingPaths(
        {{"--mesh", r.scene.scene.mesh}, {"--pattern", r.scene.scene.pattern}, {"--material", r.options.materialFile}},
        {{"--output", r.options.output}, {"--exr", r.options.exr}, {"--report", r.report}});
    RenderOptions options = r.options;
    options.progress = options.progress && !r.scene.quiet;
    if (r.surface.surfaceOnly) return runSurfaceRender(r, options);
    const Scene scene = buildScene(resolveScene(r.scene));
    printWarnings(scene);
    const RenderResult result = renderScene(scene, options);
    const nlohmann::json report = renderReport(result);
    if (!r.report.empty()) writeReport(r.report, report);
    std::printf("%s\n", report.dump().c_str());
    return 0;
}

}  // namespace knit::cli
