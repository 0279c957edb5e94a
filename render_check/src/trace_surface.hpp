// trace_surface.hpp — internal: the surface level in the tracer: the base mesh shaded with a
// surface bake (knit/bake.hpp) as the glTF export shows it (exporters' knit/surface_export.hpp):
// texture tile = one pattern period (texture coordinates (u U, 1 - v V), REPEAT), alpha MASK
// (hits where the baked coverage is below the cutoff are skipped, so the holes between loops let
// light through), albedo from the baked albedo map (nearest texel). The normal map is not used:
// the surface shades with the triangle's own normal.
#pragma once
#include <cstdint>

#include <embree3/rtcore.h>
#include <glm/vec2.hpp>

#include "knit/bake.hpp"
#include "knit/base_mesh.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/ply_material.hpp"
#include "knit/render.hpp"

namespace knit {

struct SurfaceTexture {
    const SurfaceBake* bake = nullptr;
    glm::dvec2 repeats{1.0, 1.0};  // texture tiles (pattern periods) across u and v in [0, 1]
    float alphaCutoff = 0.5f;      // MASK, as exported

    // Texel (row-major from the top) at the mesh's uv.
    size_t texel(glm::dvec2 uv) const;
    Rgb albedo(glm::dvec2 uv) const;
    Rgb transmittance(glm::dvec2 uv) const;  // black when the bake has none
    float coverage(glm::dvec2 uv) const;
};

// What the MASK filter of the base mesh's Embree geometry reads (its user data).
struct SurfaceMesh {
    const BaseMesh* mesh = nullptr;
    const SurfaceTexture* texture = nullptr;
    // The mesh's uv at a point of triangle `face` with Embree's barycentrics (u, v):
    // (1 - u - v) uv0 + u uv1 + v uv2.
    glm::dvec2 uvAt(uint32_t face, float u, float v) const;
};

// Sets the MASK filter (intersect and occlusion) on a triangle geometry of surface.mesh's faces;
// `surface` must outlive the geometry.
void setSurfaceFilter(RTCGeometry geometry, const SurfaceMesh& surface);

namespace detail {
// renderScene's steps at the surface level (RenderOptions::surface):
// a ply geometry without plies that sets the scene units (yarn radii around `centre`),
PlyGeometry surfaceFrame(const Scene& scene, const glm::dvec3& centre);
// and the texture of the bake (repeats: the options', else the scene's placement).
SurfaceTexture surfaceTexture(const Scene& scene, const RenderOptions& options);
}  // namespace detail

}  // namespace knit
