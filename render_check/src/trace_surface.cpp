// The surface level in the tracer: baked texture lookups and the alpha MASK filter of the base mesh.
#include "trace_surface.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "knit/scene.hpp"

namespace knit {
namespace {

void surfaceMaskFilter(const RTCFilterFunctionNArguments* a) {
    const SurfaceMesh& s = *static_cast<const SurfaceMesh*>(a->geometryUserPtr);
    for (unsigned i = 0; i < a->N; ++i) {
        if (a->valid[i] != -1) continue;
        const uint32_t face = RTCHitN_primID(a->hit, a->N, i);
        const glm::dvec2 uv = s.uvAt(face, RTCHitN_u(a->hit, a->N, i), RTCHitN_v(a->hit, a->N, i));
        if (s.texture->coverage(uv) < s.texture->alphaCutoff) a->valid[i] = 0;
    }
}

double fraction(double x) { return x - std::floor(x); }

}  // namespace

size_t SurfaceTexture::texel(glm::dvec2 uv) const {
    // Texture coordinates (s, t) = (u U, 1 - v V) wrapped into [0, 1): t = 0 is the top row.
    const double s = fraction(uv.x * repeats.x), t = fraction(1.0 - uv.y * repeats.y);
    const int col = std::clamp(int(s * bake->width), 0, bake->width - 1);
    const int row = std::clamp(int(t * bake->height), 0, bake->height - 1);
    return size_t(row) * size_t(bake->width) + size_t(col);
}

Rgb SurfaceTexture::albedo(glm::dvec2 uv) const {
    const size_t i = texel(uv);
    return Rgb(bake->albedo[3 * i], bake->albedo[3 * i + 1], bake->albedo[3 * i + 2]);
}

Rgb SurfaceTexture::transmittance(glm::dvec2 uv) const {
    if (bake->transmittance.empty()) return Rgb(0.0);
    const size_t i = texel(uv);
    return Rgb(bake->transmittance[3 * i], bake->transmittance[3 * i + 1], bake->transmittance[3 * i + 2]);
}

float SurfaceTexture::coverage(glm::dvec2 uv) const { return bake->coverage[texel(uv)]; }

glm::dvec2 SurfaceMesh::uvAt(uint32_t face, float u, float v) const {
    const glm::uvec3 t = mesh->faceUvs[face];
    return (1.0 - double(u) - double(v)) * mesh->uvs[t.x] + double(u) * mesh->uvs[t.y] + double(v) * mesh->uvs[t.z];
}

void setSurfaceFilter(RTCGeometry geometry, const SurfaceMesh& surface) {
    rtcSetGeometryUserData(geometry, const_cast<SurfaceMesh*>(&surface));
    rtcSetGeometryIntersectFilterFunction(geometry, surfaceMaskFilter);
    rtcSetGeometryOccludedFilterFunction(geometry, surfaceMaskFilter);
}

namespace detail {

PlyGeometry surfaceFrame(const Scene& scene, const glm::dvec3& centre) {
    PlyGeometry g;
    g.origin = centre;
    g.unit = scene.yarnRadius() > 0 ? scene.yarnRadius() : 1e-3;
    g.radius = 1.f;
    return g;
}

SurfaceTexture surfaceTexture(const Scene& scene, const RenderOptions& options) {
    SurfaceTexture t;
    t.bake = options.surface;
    t.repeats = options.surfaceRepeats[0] > 0 && options.surfaceRepeats[1] > 0
                    ? glm::dvec2(options.surfaceRepeats[0], options.surfaceRepeats[1])
                    : scene.placement().repeats;
    return t;
}

}  // namespace detail

}  // namespace knit
