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
    // Whether --bake-size was given: without it a render's view bakes at the width its surface
    // level needs (RenderOptions::viewBakeSize = 0), --surface-only at bakeSize.
    const CLI::Option* bakeSizeOption = nullptr;
    bool bakeSizeGiven() const { return bakeSizeOption != nullptr && bakeSizeOption->count() > 0; }
    // Paths per direction bin of the scattering table the renderer shades the surface level
    // with (knit/surface_scattering.hpp); render only (a file carries the baked material).
    int scatteringPaths = 0;
};

// Registers --surface-only and --bake-size on `command` (build and render); with `render` also
// --scattering-paths (default 6144).
void addSurfaceFlags(CLI::App& command, SurfaceFlags& flags, bool render = false);

struct SurfaceBuild {
    Pattern pattern;
    BaseMesh mesh;
    PatternPlacement placement;
    SurfaceBake bake;
    SurfaceExportStats exported;  // runSurfaceBuild only
};

// Throws knit::Error naming --bake-size unless it is in 1..8192.
void requireBakeSize(const SurfaceFlags& flags);

// Bakes one cell of `pattern` placed with `placement`, with the scene's ply options `plies`
// (converted to pattern units) and `material`. Throws knit::Error naming --bake-size.
SurfaceBake bakePattern(const Pattern& pattern, const PatternPlacement& placement, const PlyOptions& plies,
                        const SurfaceFlags& flags, const PlyMaterial& material);

// The baked albedo + coverage and normal maps as the 8-bit images of the glTF material.
SurfaceImages surfaceImages(const SurfaceBake& bake);

// Loads the pattern and mesh of `options` (no tiling, yarns or plies on the mesh) and bakes the
// pattern (bakePattern). Throws knit::Error naming the option (--bake-size) or file.
SurfaceBuild bakeSurfaceLevel(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material);

// bakeSurfaceLevel, then the base mesh with the baked material written to `output` (.glb,
// checked before the bake).
SurfaceBuild runSurfaceBuild(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material,
                             const std::string& output);

// A scene of the surface level for renderScene (RenderOptions::surface): the base mesh, its
// normals and the yarn radius on it, no yarns or plies.
Scene surfaceScene(const SurfaceBuild& build);

// The `"surface"` object of a report: bake size, seconds, mean coverage, texture repeats.
nlohmann::json surfaceReport(const SurfaceBuild& build);
// The `"export"` object of the report, as `knit build` writes for other exports (format, curves,
// vertices, triangles, bytes) plus the texture size (bakeWidth, bakeHeight) and PNG bytes.
nlohmann::json surfaceExportReport(const SurfaceBuild& build);

}  // namespace knit::cli
