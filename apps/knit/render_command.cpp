// `knit render`: build the scene, render it, write the report, print the report on stdout.
#include "render_command.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "path_collisions.hpp"
#include "render_flags.hpp"
#include "render_report.hpp"
#include "report.hpp"

namespace knit::cli {

void addRenderCommand(CLI::App& app, RenderCommand& r) {
    r.command = app.add_subcommand("render", "Path-trace the knit on its base mesh (front- or back-lit)");
    addSceneFlags(*r.command, r.scene);
    addRenderFlags(*r.command, r.options);
    addViewFlags(*r.command, r.view, r.options.fovDegrees, r.options.width, r.options.height, Detail::View);
    r.command->add_option("--report", r.report, "Write a JSON report (time, rays/s, memory)");
    r.command->footer(kSceneHelp);
}

int runRender(const RenderCommand& r) {
    checkReportPath(r.report);  // before the scene and the render: the same check as `build`
    refuseCollidingPaths(
        {{"--mesh", r.scene.scene.mesh}, {"--pattern", r.scene.scene.pattern}, {"--material", r.options.materialFile}},
        {{"--output", r.options.output}, {"--exr", r.options.exr}, {"--report", r.report}});
    // Step 1: the camera (validated before any work) and the detail the view asks for.
    RenderOptions options = r.options;
    options.progress = options.progress && !r.scene.quiet;
    const ImageSize image{options.fovDegrees, options.width, options.height};
    options.view = givenView(r.view, image);
    SceneOptions sceneOptions = resolveScene(r.scene);
    sceneOptions.detail =
        detailOptions(r.view, image, options.light == LightPlacement::Back, options.mode == GeometryMode::Curves);
    // Step 2: the scene, the render and the report (with the camera and the levels).
    const Scene scene = buildScene(sceneOptions);
    printWarnings(scene);
    const RenderResult result = renderScene(scene, options);
    nlohmann::json report = renderReport(result);
    report["camera"] = cameraJson(result.view);
    report["levels"] = levelsJson(levelStats(scene));
    if (!r.report.empty()) writeReport(r.report, report);
    std::printf("%s\n", report.dump().c_str());
    return 0;
}

}  // namespace knit::cli
