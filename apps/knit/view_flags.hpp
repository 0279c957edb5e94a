// view_flags.hpp — the view flags `knit build` and `knit render` share (--eye --target --up --fov
// --width --height --detail), how they become a knit::View and DetailOptions, and the "camera"
// and "levels" parts of both reports.
#pragma once
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "knit/scene.hpp"

namespace knit::cli {

// The image the view is for (--fov --width --height).
struct ImageSize {
    double fovDegrees = 30;
    int width = 512, height = 384;
};

// full: the whole scene at ply detail (today's output); view: only what the view needs.
enum class Detail { Full, View };

struct ViewFlags {
    std::vector<double> eye, target, up;  // empty, or X Y Z
    Detail detail = Detail::Full;
    // --ply-pixels, --yarn-pixels: the projected radius (pixels) at which a cell gets plies or
    // yarn curves (DetailOptions' enter thresholds; a cell keeps its level down to 0.8 of them).
    double plyPixels = DetailOptions{}.plyPixels.enter;
    double yarnPixels = DetailOptions{}.yarnPixels.enter;
    ImageSize image;  // build's --fov --width --height (render binds them to its RenderOptions)
};

// Registers --eye --target --up --detail (default `defaultDetail`) --ply-pixels --yarn-pixels and
// --fov --width --height bound to the three given fields.
// `levelThresholds` false: no --ply-pixels / --yarn-pixels (a command that picks every level itself).
void addViewFlags(CLI::App& command, ViewFlags& flags, double& fovDegrees, int& width, int& height,
                  Detail defaultDetail, bool levelThresholds = true);

// The camera the flags give (none without --eye), with the image fields; validated (knit::Error
// naming the option). --up defaults to +y (glTF's up).
std::optional<View> givenView(const ViewFlags& flags, const ImageSize& image);

// With --detail view: the detail options for the given camera (or the default framing at the
// image's size) and thresholds (knit::Error naming --ply-pixels / --yarn-pixels unless positive).
// `backLit` keeps back faces; `yarnCurves` false gives yarn-level cells plies (for a consumer that
// draws every cell with plies).
std::optional<DetailOptions> detailOptions(const ViewFlags& flags, const ImageSize& image, bool backLit,
                                           bool yarnCurves);

// "camera": {"eye", "target", "up", "fovDegrees"}.
nlohmann::json cameraJson(const View& view);
// "levels": {"plies", "yarns", "surface"} with cells, yarnVertices, plyVertices, bytes; the
// surface's "textured" says whether its base mesh was drawn with the baked pattern (render) or
// not at all / plain (build exports the ply level only).
nlohmann::json levelsJson(const LevelStats& levels, bool surfaceTextured);

}  // namespace knit::cli
