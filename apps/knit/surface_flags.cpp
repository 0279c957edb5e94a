// --surface-only / --bake-size: bake the pattern cell, write the base mesh with the baked material.
#include "surface_flags.hpp"

#include <nlohmann/json.hpp>

#include "knit/error.hpp"

namespace knit::cli {

void addSurfaceFlags(CLI::App& command, SurfaceFlags& flags, bool render) {
    command.add_flag("--surface-only", flags.surfaceOnly,
                     "The surface level: the base mesh with the knit baked into tileable textures instead of "
                     "yarns or plies (build: a glTF PBR material, .glb; render: traced with the baked albedo and "
                     "coverage)");
    flags.bakeSizeOption =
        command
            .add_option("--bake-size", flags.bakeSize,
                        render ? "Baked texture width in pixels per pattern period (1..8192); --surface-only: default "
                                 "256; a view's surface level: default 4 texels per pixel where its pattern period "
                                 "looks largest, 64..256"
                               : "Baked texture width in pixels per pattern period (1..8192)")
            ->capture_default_str();
    if (!render) return;
    flags.scatteringPaths = 6144;
    command
        .add_option("--scattering-paths", flags.scatteringPaths,
                    "Paths per direction bin, on average (288 bins; most go to the directions the camera and the "
                    "light need), of the measured scattering the surface level is shaded with (how the plies "
                    "reflect, transmit and let light through their holes for every light and view direction); "
                    "0 = the exported material's Lambertian albedo and coverage mask (0..1048576)")
        ->capture_default_str();
}

void requireBakeSize(const SurfaceFlags& flags) {
    if (flags.bakeSize < 1 || flags.bakeSize > 8192)
        throw Error("--bake-size must be in 1..8192 (got " + std::to_string(flags.bakeSize) + ")");
}

SurfaceBake bakePattern(const Pattern& pattern, const PatternPlacement& placement, const PlyOptions& plies,
                        const SurfaceFlags& flags, const PlyMaterial& material) {
    requireBakeSize(flags);
    BakeOptions bo;
    bo.width = flags.bakeSize;
    bo.plies = patternPlyOptions(plies, pattern, placement.scale);
    const glm::dvec2 stretch = placementStretch(pattern, placement);
    bo.stretch[0] = stretch.x, bo.stretch[1] = stretch.y;
    bo.material = material;
    bo.scatteringPaths = flags.scatteringPaths;
    return bakeSurface(pattern, bo);
}

SurfaceImages surfaceImages(const SurfaceBake& bake) {
    SurfaceImages images;
    images.width = bake.width, images.height = bake.height;
    images.baseColorRgba = baseColorRgba8(bake);
    images.normalRgb = normalRgb8(bake);
    return images;
}

SurfaceBuild bakeSurfaceLevel(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material) {
    requireBakeSize(flags);  // before loading anything
    // Step 1: pattern, mesh and placement only: the surface level needs no yarns on the mesh.
    SurfaceBuild b;
    b.pattern = loadPatternFileOrName(options.pattern);
    b.mesh = loadMeshFileOrName(options.mesh, options.meshOptions);
    b.placement = placePattern(b.pattern, b.mesh, options.placement);
    // Step 2: the bake of one pattern cell.
    b.bake = bakePattern(b.pattern, b.placement, options.plies, flags, material);
    return b;
}

SurfaceBuild runSurfaceBuild(const SceneOptions& options, const SurfaceFlags& flags, const PlyMaterial& material,
                             const std::string& output) {
    checkSurfaceOutput(output);
    SurfaceBuild b = bakeSurfaceLevel(options, flags, material);
    // The base mesh with the baked material, one texture tile per pattern period.
    SurfaceExportOptions eo;
    eo.path = output;
    eo.repeats = b.placement.repeats;
    b.exported = exportSurface(b.mesh, surfaceImages(b.bake), eo);
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
