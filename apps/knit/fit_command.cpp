// `knit fit`: read the photographs, build the scene, fit the material, write it and the report.
#include "fit_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "knit/error.hpp"
#include "knit/image_io.hpp"
#include "path_collisions.hpp"
#include "render_flags.hpp"
#include "report.hpp"

namespace knit::cli {
namespace {

// "loss 0.123 kR=0.30 kTT=0.10 ..." for the progress lines.
void printIteration(const FitIteration& it, const std::vector<std::string>& labels) {
    std::string line = "fit: evaluation " + std::to_string(it.evaluation) + (it.stage == 0 ? " (coarse)" : "") +
                       " loss " + std::to_string(it.loss);
    for (size_t i = 0; i < it.values.size() && i < labels.size(); ++i)
        line += " " + labels[i] + "=" + std::to_string(it.values[i]);
    std::fprintf(stderr, "%s\n", line.c_str());
}

nlohmann::json lossJson(const ImageLoss& l) {
    return {{"rmse", l.rmse}, {"ssim", l.ssim}, {"relativeL2", l.relativeL2}, {"loss", l.total}};
}

// The report and, next to it, the fitted renders and the side-by-side image.
void writeFitReport(const std::string& path, const FitResult& r, const Image& front, const Image& back,
                    const Scene& scene) {
    const std::filesystem::path p(path);
    const std::string stem = (p.parent_path() / p.stem()).string();
    const std::string frontPng = stem + "_front.png", backPng = stem + "_back.png",
                      sidePng = stem + "_side_by_side.png";
    writePng(frontPng, r.frontRender);
    writePng(backPng, r.backRender);
    writePng(sidePng, sideBySide(front, r.frontRender, back, r.backRender));
    nlohmann::json history = nlohmann::json::array();
    for (const FitIteration& it : r.history)
        history.push_back({{"evaluation", it.evaluation},
                           {"stage", it.stage == 0 ? "coarse" : "full"},
                           {"loss", it.loss},
                           {"frontLoss", it.frontLoss},
                           {"backLoss", it.backLoss},
                           {"values", it.values}});
    nlohmann::json params = nlohmann::json::object();
    for (size_t i = 0; i < r.labels.size(); ++i) params[r.labels[i]] = r.values[i];
    nlohmann::json report = {
        {"parameters", params},     {"material", nlohmann::json::parse(materialJsonText(r.material))},
        {"loss", r.loss},           {"front", lossJson(r.front)},
        {"back", lossJson(r.back)}, {"seconds", r.seconds},
        {"renders", r.renders},     {"stopReason", r.stopReason},
        {"warnings", r.warnings},   {"images", {frontPng, backPng, sidePng}},
        {"history", history}};
    report["detail"] = scene.detail() ? "view" : "full";
    if (scene.detail()) report["levels"] = levelsJson(levelStats(scene), false);  // what the fit traced
    writeReport(path, report);
}

// The scene the fit renders. With --detail view only the cells the camera sees are built (frustum
// culling with the shadow margin; back faces kept, since the back-lit photograph sees light come
// through the cloth), every one of them at the ply level: the fit compares plies with what the
// photographs show, and a surface-level bake would depend on the material being fitted.
SceneOptions fitSceneOptions(const FitCommand& f, int width, int height) {
    SceneOptions options = resolveScene(f.scene);
    std::optional<DetailOptions> detail =
        detailOptions(f.view, {f.fit.render.fovDegrees, width, height}, /*backLit=*/true, /*yarnCurves=*/false);
    if (detail) {
        detail->plyPixels = {0.0, 0.0};  // every visible cell at the ply level
        options.detail = detail;
    }
    return options;
}

}  // namespace

void addFitCommand(CLI::App& app, FitCommand& f) {
    f.command = app.add_subcommand("fit", "Fit the ply material to a front-lit and a back-lit photograph");
    addSceneFlags(*f.command, f.scene);
    addRenderFlags(*f.command, f.fit.render);
    // The camera as render takes it (--eye --target --up --fov) and --detail (default view, as
    // render's). The photographs fix the image size and both lights are rendered: those flags go.
    addViewFlags(*f.command, f.view, f.fit.render.fovDegrees, f.viewWidth, f.viewHeight, Detail::View,
                 /*levelThresholds=*/false);  // every visible cell at the ply level
    for (const char* flag : {"--light", "--output", "--exr", "--width", "--height"})
        f.command->remove_option(f.command->get_option(flag));
    f.command->add_option("--front", f.front, "Front-lit photograph (PNG sRGB or EXR linear)")->required();
    f.command->add_option("--back", f.back, "Back-lit photograph, same size")->required();
    f.command->add_option("-o,--output", f.output, "Fitted material JSON (knit render --material reads it)")
        ->required();
    f.command->add_option("--fit", f.fitList, "Fields to fit (comma separated; see docs/fitting.md)")
        ->capture_default_str();
    f.command->add_option("--bound", f.bounds, "Bounds of a fitted field: NAME=LO:HI (repeatable)");
    f.command->add_option("--mask", f.mask, "Mask image of the photographs' size (0 = ignore a pixel)");
    f.command->add_option("--budget", f.fit.budgetSeconds, "Time budget in seconds")->capture_default_str();
    f.command->add_option("--max-evaluations", f.fit.maxEvaluations, "Loss evaluations (2 renders each)")
        ->capture_default_str();
    f.command->add_option("--report", f.report, "JSON report; the fitted renders are written beside it");
    f.command->footer(kSceneHelp);
}

int runFit(const FitCommand& f) {
    // Step 1: check the outputs, read the photographs and the mask.
    checkReportPath(f.report);
    checkReportPath(f.output);
    refuseCollidingPaths({{"--front", f.front},
                          {"--back", f.back},
                          {"--mask", f.mask},
                          {"--mesh", f.scene.scene.mesh},
                          {"--pattern", f.scene.scene.pattern},
                          {"--material", f.fit.render.materialFile}},
                         {{"-o", f.output}, {"--report", f.report}});
    // After the collisions (an output onto an input is the more useful message).
    refuseOtherFormatName("-o", f.output, "a JSON file", ".json");
    const FitTarget front = readFitTarget(f.front, "--front"), back = readFitTarget(f.back, "--back");
    checkFitTargets(front, back, {});
    // The camera of the photographs (none: render's default framing), checked before the scene.
    const std::optional<View> camera =
        givenView(f.view, {f.fit.render.fovDegrees, front.image.width, front.image.height});
    const std::vector<float> mask =
        f.mask.empty() ? std::vector<float>{} : readMask(f.mask, "--mask", front.image.width, front.image.height);
    // Step 2: the free fields and their bounds.
    FitOptions options = f.fit;
    options.parameters = parseFitList(f.fitList, "--fit");
    for (const std::string& b : f.bounds) applyFitBound(options.parameters, b, "--bound");
    options.render.progress = false;
    options.render.view = camera;
    const std::vector<std::string> labels = FitSpace(options.parameters, resolveMaterial(options.render)).labels();
    if (!f.scene.quiet) options.progress = [labels](const FitIteration& it) { printIteration(it, labels); };
    // Step 3: the scene, the fit, the outputs.
    const Scene scene = buildScene(fitSceneOptions(f, front.image.width, front.image.height));
    printWarnings(scene);
    const FitResult result = fitMaterial(scene, front, back, mask, options);
    for (const std::string& w : result.warnings) std::fprintf(stderr, "knit fit: warning: %s\n", w.c_str());
    writeReport(f.output, nlohmann::json::parse(materialJsonText(result.material)));
    if (!f.report.empty()) writeFitReport(f.report, result, front.image, back.image, scene);
    if (!f.scene.quiet)
        std::fprintf(stderr, "fit: %s after %d renders in %.1f s; loss %.4g (front SSIM %.3f, back SSIM %.3f)\n",
                     result.stopReason.c_str(), result.renders, result.seconds, result.loss, result.front.ssim,
                     result.back.ssim);
    return 0;
}

}  // namespace knit::cli
