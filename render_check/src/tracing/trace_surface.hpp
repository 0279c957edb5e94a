// trace_surface.hpp — internal: the surface level in the tracer: the base mesh shaded with a
// surface bake (knit/bake.hpp) as the glTF export shows it (exporters' knit/surface_export.hpp):
// texture tile = one pattern period (texture coordinates (u U, 1 - v V), REPEAT), alpha MASK
// (hits where the baked coverage is below the cutoff are skipped, so the holes between loops let
// light through), albedo from the baked albedo map (nearest texel). The normal map is not used:
// the surface shades with the triangle's own normal. A bake with a scattering table
// (knit/surface_scattering.hpp) is shaded with the table instead, in the triangle's tangent
// space, and its holes open with the viewing angle (stochastic transparency, not the MASK).
#pragma once
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec2.hpp>

#include "knit/bake.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/base_mesh.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/ply_material.hpp"
#include "knit/render.hpp"

namespace knit {

struct SurfaceTexture {
    const SurfaceBake* bake = nullptr;
    glm::dvec2 repeats{1.0, 1.0};  // texture tiles (pattern periods) across u and v in [0, 1]
    float alphaCutoff = 0.5f;      // MASK, as exported (without a scattering table)
    Rgb meanAlbedo{0.0};           // coverage-weighted mean of the baked albedo (makeSurfaceTexture)
    double meanHoles = 0;          // 1 - the bake's mean coverage (makeSurfaceTexture)
    // Camera rays (from `eye`, scene units) see a texel footprint of pixelAngle x distance: with a
    // table they read the tint and the holes prefiltered over it (a box pyramid, as a client's
    // mipmaps), which is what the pixel averages anyway, with less noise. 0: never.
    double pixelAngle = 0;
    glm::vec3 eye{0.f};

    // Texel (row-major from the top) at the mesh's uv.
    size_t texel(glm::dvec2 uv) const;
    Rgb albedo(glm::dvec2 uv) const;
    Rgb transmittance(glm::dvec2 uv) const;  // black when the bake has none
    float coverage(glm::dvec2 uv) const;
    // The bake's scattering table, or null when it has none (then: MASK and Lambertian albedo).
    const SurfaceScattering* scattering() const;
    // With a table: the baked albedo relative to its mean (the pattern's colours across the cell;
    // the table holds the cell's mean), per channel, averaged over 2^level x 2^level texels.
    Rgb tint(glm::dvec2 uv, int level = 0) const;
    // With a table: the probability that a line seen from `out` (tangent space) crosses the cloth
    // at uv through a hole: the table's pass fraction for `out`, spread over the cell as the
    // baked holes (1 - coverage) are, averaged over 2^level x 2^level texels.
    double passThrough(glm::dvec2 uv, const glm::dvec3& out, int level = 0) const;

    // Box pyramid of the tint (RGB, weighted by the coverage: what a hit sees) and of the holes
    // relative to their mean, level 0 = the bake's texels, level k averaging the 2^k x 2^k texels
    // of level 0 it covers (clipped at the image's edge); makeSurfaceTexture.
    struct Level {
        int width = 0, height = 0;
        std::vector<float> tint;   // 3 per texel
        std::vector<float> holes;  // (1 - coverage) / meanHoles
    };
    std::vector<Level> levels;
    int maxLevel() const { return levels.empty() ? 0 : int(levels.size()) - 1; }
};

// The texture of a bake repeated `repeats` times across the mesh's uv range.
SurfaceTexture makeSurfaceTexture(const SurfaceBake& bake, glm::dvec2 repeats);

// What the surface filter of the base mesh's Embree geometry reads (its user data).
struct SurfaceMesh {
    const BaseMesh* mesh = nullptr;
    const SurfaceTexture* texture = nullptr;
    // The mesh's uv at a point of triangle `face` with Embree's barycentrics (u, v):
    // (1 - u - v) uv0 + u uv1 + v uv2.
    glm::dvec2 uvAt(uint32_t face, float u, float v) const;
    // Tangent space of triangle `face` (the bake's: x along +u, y along +v, z its counter-clockwise
    // normal, the cloth's front); an arbitrary x, y around z where the uv are degenerate.
    ShadingFrame frame(uint32_t face) const;
    double unit = 1;  // metres per scene unit (the renderer's)
    // The pyramid level a camera ray from texture->eye sees at distance t (scene units) along
    // `dir` on `face`: log2 of its footprint in texels (foreshortened), 0 for other rays.
    int level(uint32_t face, const glm::vec3& org, const glm::vec3& dir, float t) const;
};

// Sets the surface filter (intersect and occlusion) on a triangle geometry of surface.mesh's
// faces: without a scattering table the MASK (hits below the cutoff are skipped); with one, a hit
// is skipped with the probability passThrough (a random number hashed from the ray and the
// triangle: stochastic transparency). `surface` must outlive the geometry.
void setSurfaceFilter(RTCGeometry geometry, const SurfaceMesh& surface);

namespace impl {
// renderScene's steps at the surface level (RenderOptions::surface):
// a ply geometry without plies that sets the scene units (yarn radii around `centre`),
PlyGeometry surfaceFrame(const Scene& scene, const glm::dvec3& centre);
// and the texture of the bake (repeats: the options', else the scene's placement).
SurfaceTexture surfaceTexture(const Scene& scene, const RenderOptions& options);
// Where a camera at `eye` sees `mesh` from and a light at `light` lights it from: per triangle
// (at most `maxTriangles`, evenly strided), the directions to the eye and to the light in the
// triangle's tangent space (SurfaceMesh::frame), each weighted by the triangle's share of the
// image (area x |cos| towards the eye / distance^2). For BakeOptions::scatteringFocus.
std::vector<ScatteringFocus> scatteringFocus(const BaseMesh& mesh, const glm::dvec3& eye, const glm::dvec3& light,
                                             size_t maxTriangles = 8192);
}  // namespace impl

}  // namespace knit
