// build_command.hpp — `knit build`: build the scene and export it (curves or tubes), with an
// optional JSON report.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "knit/export.hpp"
#include "scene_flags.hpp"
#ifdef KNIT_HAVE_RENDER_CHECK
#include "surface_flags.hpp"
#endif
#include "view_flags.hpp"

namespace knit::cli {

struct BuildCommand {
    CLI::App* command = nullptr;  // set by addBuildCommand
    SceneFlags scene;
    ExportOptions exportOptions;  // -o defaults to knit-plies.obj
    std::string report;           // --report path; empty = none
    std::string rest;             // --rest: bind on this mesh, evaluate on --mesh (same connectivity)
#ifdef KNIT_HAVE_RENDER_CHECK
    SurfaceFlags surface;  // --surface-only --bake-size: the base mesh with the baked knit material
#endif
    ViewFlags view;  // --eye --target --up --fov --width --height --detail (default full)
};

// Registers the subcommand and its flags on `app`, bound to `build` (which must outlive parsing).
void addBuildCommand(CLI::App& app, BuildCommand& build);

// Builds and exports; prints a summary on stdout. Throws knit::Error on bad input.
int runBuild(const BuildCommand& build);

}  // namespace knit::cli
