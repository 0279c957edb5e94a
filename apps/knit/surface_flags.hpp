// surface_flags.hpp — the surface level of detail on the command line: `--surface-only` and
// `--bake-size N` (knit build; a view's surface cells reuse runSurfaceBuild). The base mesh is
// written with the pattern baked into tileable textures (render_check's knit/bake.hpp) as a glTF
// PBR material (exporters' knit/surface_export.hpp) instead of yarns or plies.
#pragma once
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>

#include "knit/bake.hpp"
#include "knit/scene.hpp"
#include "knit/surface_export.hpp"

namespace knit::cli {

struct SurfaceFlags {
    bool surfaceOnly = false;
    int bakeSize = 256;  // texture width in pixels (one pattern period); height from the aspect
};

// Registers --surface-only and --bake-size on `command`.
void addSurfaceFlags(CLI::App& command, SurfaceFlags& flags);

struct SurfaceBuild {
    Pattern pattern;
    BaseMesh mesh;
    PatternPlacement placement;
    SurfaceBake bake;
    SurfaceExportStats exported;
};

// Loads the pattern and mesh of `options` (no tiling, yarns or plies on the mesh), bakes the
// pattern with the scene's ply options (converted to pattern units) and `material`, and writes
// the base mesh with the baked material to `output` (.glb). Throws knit::Error naming the
// option (--bake-size) or file.
SurfaceBuild runSurfaceBuild(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material,
                             const std::string& output);

// The `"surface"` object of a report: bake size, coverage, seconds, export counts and bytes.
nlohmann::json surfaceReport(const SurfaceBuild& build);
// The `"export"` object of the report, as `knit build` writes for other exports (format, curves,
// vertices, triangles, bytes) plus the texture size (bakeWidth, bakeHeight).
nlohmann::json surfaceExportReport(const SurfaceBuild& build);

}  // namespace knit::cli
