// `knit render`: build the scene, render it, write the report, print the report on stdout.
#include "render_command.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "knit/output_transaction.hpp"
#include "path_collisions.hpp"
#include "render_flags.hpp"
#include "render_report.hpp"
#include "report.hpp"

namespace knit::cli {

void addRenderCommand(CLI::App& app, RenderCommand& r) {
    r.command = app.add_subcommand("render", "Path-trace the knit on its base mesh (front- or back-lit)");
    addSceneFlags(*r.command, r.scene);
    addRenderFlags(*r.command, r.options);
    r.command->add_option("--report", r.report, "Write a JSON report (time, rays/s, memory)");
    r.command->footer(kSceneHelp);
}

int runRender(const RenderCommand& r) {
    checkReportPath(r.report);  // before the scene and the render: the same check as `build`
    refuseCollidingPaths(
        {{"--mesh", r.scene.scene.mesh}, {"--pattern", r.scene.scene.pattern}, {"--material", r.options.materialFile}},
        {{"--output", r.options.output}, {"--exr", r.options.exr}, {"--report", r.report}});
    // The PNG, the EXR and the report are staged and committed together at the end.
    OutputTransaction outputs;
    RenderOptions options = r.options;
    options.progress = options.progress && !r.scene.quiet;
    options.output = outputs.stage(r.options.output);
    options.exr = outputs.stage(r.options.exr);
    const SceneOptions sceneOptions = resolveScene(r.scene);
    options.budget = sceneOptions.budget;  // --max-memory
    const Scene scene = buildScene(sceneOptions);
    printWarnings(scene);
    RenderResult result = outputs.run([&] { return renderScene(scene, options); });
    for (std::string& path : result.written) path = outputs.finalNames(path);
    const nlohmann::json report = renderReport(result);
    if (!r.report.empty()) outputs.run([&] { writeReport(outputs.stage(r.report), report); });
    outputs.run([&] { outputs.commit(); });
    std::printf("%s\n", report.dump().c_str());
    return 0;
}

}  // namespace knit::cli
