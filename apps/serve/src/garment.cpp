// The garment for a view, as a GLB of yarn centrelines (garment.hpp).
#include "garment.hpp"

#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/scene.hpp"

namespace knit::serve {
namespace {

SceneOptions sceneOptions(const GarmentSettings& settings, const StageFn& stage) {
    SceneOptions options;
    options.buildPlies = false;
    options.placement.repeats = {settings.repeats[0], settings.repeats[1]};
    options.placement.gauge = settings.gauge;
    options.budget = settings.budget;
    options.progress = stage;
    DetailOptions detail;
    detail.view = settings.view;
    // The page draws yarn curves for every cell it sees: no cell is left to the surface level.
    detail.yarnPixels = {1e-9, 0.0};
    detail.plyPixels = {1e9, 1e9};
    options.detail = detail;
    return options;
}

nlohmann::json cameraJson(const View& v) {
    return {{"eye", {v.eye.x, v.eye.y, v.eye.z}},
            {"target", {v.target.x, v.target.y, v.target.z}},
            {"up", {v.up.x, v.up.y, v.up.z}},
            {"fov", v.fovDegrees}};
}

}  // namespace

nlohmann::json writeGarmentGlb(const Pattern& pattern, const BaseMesh& mesh, const GarmentSettings& settings,
                               const std::string& glbPath, const StageFn& stage) {
    const Scene built = buildScene(pattern, mesh, sceneOptions(settings, stage));
    // The yarn pieces of the cells the view keeps (no cell is at the ply level: no ply pieces).
    const Scene visible = viewPiecesScene(built, false);
    const Polylines& curves = visible.yarns().curves;
    // A line-strip point is 12 bytes of position, 4 of radius and 4 of colour; closed curves
    // repeat their first point.
    const double estimate =
        20.0 * double(curves.pointCount() + curves.curveCount()) + 1024.0 * double(curves.curveCount());
    if (estimate > double(settings.maxFileBytes))
        throw Error("the garment's yarns would take about " + std::to_string(int64_t(estimate / 1048576)) +
                    " MB, over the page's limit of " + std::to_string(settings.maxFileBytes >> 20) +
                    " MB; lower the repeats or the gauge, or look from farther away");
    if (curves.curveCount() == 0) throw Error("the view sees none of the garment; turn the camera towards it");
    ExportOptions exportOptions;
    exportOptions.path = glbPath;
    exportOptions.what = ExportWhat::Yarns;
    exportOptions.budget = settings.budget;
    const ExportStats stats = exportScene(visible, exportOptions);
    const LevelStats levels = levelStats(built);
    return {{"yarns", curves.curveCount()},
            {"points", curves.pointCount()},
            {"bytes", stats.bytes},
            {"cells", built.grid().cells.size()},
            {"culled_cells", levels.culledCells},
            {"repeats", {built.placement().repeats.x, built.placement().repeats.y}},
            {"camera", cameraJson(built.detail()->view)}};
}

}  // namespace knit::serve
