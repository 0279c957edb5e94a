// --surface-only / --bake-size: bake the pattern cell, write the base mesh with the baked material.
#include "surface_flags.hpp"

#include <nlohmann/json.hpp>

#include "knit/error.hpp"

namespace knit::cli {

void addSurfaceFlags(CLI::App& command, SurfaceFlags& flags) {
    command.add_flag("--surface-only", flags.surfaceOnly,
                     "The surface level: the base mesh with the knit baked into tileable textures instead of "
                     "yarns or plies (build: a glTF PBR material, .glb; render: traced with the baked albedo and "
                     "coverage)");
    command.add_option("--bake-size", flags.bakeSize, "Baked texture width in pixels per pattern period (1..8192)")
        ->capture_default_str();
}

SurfaceBuild bakeSurfaceLevel(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material) {
    if (flags.bakeSize < 1 || flags.bakeSize > 8192)
        throw Error("--bake-size must be in 1..8192 (got " + std::to_string(flags.bakeSize) + ")");
    // Step 1: pattern, mesh and placement only: the surface level needs no yarns on the mesh.
    SurfaceBuild b;
    b.pattern = loadPatternFileOrName(options.pattern);
    b.mesh = loadMeshFileOrName(options.mesh, options.meshOptions);
    b.placement = placePattern(b.pattern, b.mesh, options.placement);
    // Step 2: the bake of one pattern cell.
    BakeOptions bo;
    bo.width = flags.bakeSize;
    bo.plies = patternPlyOptions(options.plies, b.pattern, b.placement.scale);
    bo.material = material;
    b.bake = bakeSurface(b.pattern, bo);
    return b;
}

SurfaceBuild runSurfaceBuild(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material,
                             const std::string& output) {
    checkSurfaceOutput(output);
    SurfaceBuild b = bakeSurfaceLevel(options, flags, material);
    // The base mesh with the baked material, one texture tile per pattern period.
    SurfaceImages images;
    images.width = b.bake.width, images.height = b.bake.height;
    images.baseColorRgba = baseColorRgba8(b.bake);
    images.normalRgb = normalRgb8(b.bake);
    SurfaceExportOptions eo;
    eo.path = output;
    eo.repeats = b.placement.repeats;
    b.exported = exportSurface(b.mesh, images, eo);
    return b;
}

Scene surfaceScene(const SurfaceBuild& b) {
    SceneParts parts;
    parts.mesh = b.mesh;
    parts.normals = vertexNormals(b.mesh.positions, b.mesh.faces);
    parts.yarnRadius = b.pattern.radius * b.placement.scale;
    return Scene::fromParts(std::move(parts));
}

nlohmann::json surfaceReport(const SurfaceBuild& b) {
    return {{"bakeWidth", b.bake.width},
            {"bakeHeight", b.bake.height},
            {"bakeSeconds", b.bake.seconds},
            {"meanCoverage", b.bake.meanCoverage()},
            {"repeats", {b.placement.repeats.x, b.placement.repeats.y}}};
}

nlohmann::json surfaceExportReport(const SurfaceBuild& b) {
    return {{"format", "glb"},
            {"curves", 0},
            {"vertices", b.exported.vertices},
            {"triangles", b.exported.triangles},
            {"bytes", b.exported.bytes},
            {"imageBytes", b.exported.imageBytes},
            {"bakeWidth", b.bake.width},
            {"bakeHeight", b.bake.height}};
}

}  // namespace knit::cli
