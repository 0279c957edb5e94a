// render_command.hpp — `knit render`: build the scene and path-trace its plies (front- or
// back-lit); prints the render report as one JSON line.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "knit/render.hpp"
#include "scene_flags.hpp"
#include "surface_flags.hpp"
#include "view_flags.hpp"

namespace knit::cli {

struct RenderCommand {
    CLI::App* command = nullptr;  // set by addRenderCommand
    SceneFlags scene;
    RenderOptions options;
    ViewFlags view;         // --fov --width --height fill options
    std::string report;     // --report path; empty = none
    SurfaceFlags surface;   // --surface-only --bake-size: trace the base mesh with the baked knit
    std::string bound;      // --bound: a bound scene file (`knit bind`), rendered at full detail
    std::string frameMesh;  // --frame-mesh: the pose to render with --bound (default: the rest pose)
};

// Registers the subcommand and its flags on `app`, bound to `render` (which must outlive parsing).
void addRenderCommand(CLI::App& app, RenderCommand& render);

// Builds the scene, renders, writes the images and the report. Throws knit::Error on bad input.
int runRender(const RenderCommand& render);

}  // namespace knit::cli
