// The view flags of `knit build` and `knit render` (see view_flags.hpp).
#include "view_flags.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "choice.hpp"
#include "knit/error.hpp"

namespace knit::cli {
namespace {

glm::dvec3 vec3Of(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

nlohmann::json levelJson(const LevelStats::Level& l) {
    return {{"cells", l.cells}, {"yarnVertices", l.yarnVertices}, {"plyVertices", l.plyVertices}, {"bytes", l.bytes}};
}

}  // namespace

void addViewFlags(CLI::App& app, ViewFlags& f, double& fovDegrees, int& width, int& height, Detail defaultDetail,
                  bool levelThresholds) {
    f.detail = defaultDetail;
    CLI::Option* eye =
        app.add_option("--eye", f.eye, "Camera position X Y Z (metres); without it the default camera")->expected(3);
    app.add_option("--target", f.target, "Point the camera looks at, X Y Z (needs --eye)")->expected(3)->needs(eye);
    app.add_option("--up", f.up, "Image up direction X Y Z (needs --eye; default 0 1 0)")->expected(3)->needs(eye);
    eye->needs("--target");
    app.add_option("--fov", fovDegrees, "Vertical field of view (degrees)");
    app.add_option("--width", width, "Image width in pixels");
    app.add_option("--height", height, "Image height in pixels");
    addChoice(app, "--detail", f.detail, Choices<Detail>{{"full", Detail::Full}, {"view", Detail::View}},
              std::string("full: everything at ply detail; view: cull per UV cell and pick plies / yarns / surface "
                          "by projected size (default ") +
                  (defaultDetail == Detail::Full ? "full" : "view") + ")");
    if (!levelThresholds) return;
    app.add_option("--ply-pixels", f.plyPixels,
                   "With --detail view: a cell gets plies where a ply's radius covers this many pixels (kept down to "
                   "0.8 of it when the camera moves; smaller: more plies, closer to --detail full)")
        ->capture_default_str();
    app.add_option("--yarn-pixels", f.yarnPixels,
                   "With --detail view: a cell below the ply level gets yarn curves where a yarn's radius covers "
                   "this many pixels, and the textured base mesh below that")
        ->capture_default_str();
}

std::optional<View> givenView(const ViewFlags& f, const ImageSize& image) {
    if (f.eye.empty()) return std::nullopt;
    View v;
    v.eye = vec3Of(f.eye);
    v.target = vec3Of(f.target);
    if (!f.up.empty()) v.up = vec3Of(f.up);
    v.fovDegrees = image.fovDegrees, v.width = image.width, v.height = image.height;
    validateView(v);
    return v;
}

std::optional<DetailOptions> detailOptions(const ViewFlags& f, const ImageSize& image, bool backLit, bool yarnCurves) {
    for (const auto& [name, value] : {std::pair<const char*, double>{"--ply-pixels", f.plyPixels},
                                      std::pair<const char*, double>{"--yarn-pixels", f.yarnPixels}})
        if (!(value > 0) || !std::isfinite(value))
            throw Error(std::string(name) + " must be a positive number of pixels (got " + std::to_string(value) + ")");
    if (f.detail == Detail::Full) return std::nullopt;
    DetailOptions d;
    d.view = givenView(f, image);
    d.viewSettings.fovDegrees = image.fovDegrees, d.viewSettings.width = image.width;
    d.viewSettings.height = image.height;
    validateView(d.view.value_or(d.viewSettings));
    d.backLit = backLit;
    d.yarnLevel = yarnCurves;
    d.plyPixels = {f.plyPixels, 0.8 * f.plyPixels};
    d.yarnPixels = {f.yarnPixels, 0.8 * f.yarnPixels};
    return d;
}

nlohmann::json cameraJson(const View& v) {
    return {{"eye", {v.eye.x, v.eye.y, v.eye.z}},
            {"target", {v.target.x, v.target.y, v.target.z}},
            {"up", {v.up.x, v.up.y, v.up.z}},
            {"fovDegrees", v.fovDegrees}};
}

nlohmann::json levelsJson(const LevelStats& l, bool surfaceTextured) {
    nlohmann::json surface = levelJson(l.surface);
    surface["textured"] = surfaceTextured;
    return {{"plies", levelJson(l.plies)},
            {"yarns", levelJson(l.yarns)},
            {"surface", surface},
            {"culledCells", l.culledCells}};
}

}  // namespace knit::cli
