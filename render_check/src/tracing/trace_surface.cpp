// The surface level in the tracer: baked texture lookups and the alpha MASK filter of the base mesh.
#include "trace_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "knit/scene.hpp"

namespace knit {
namespace {

uint64_t mix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

uint64_t bitsOf(float f) {
    uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

// A uniform number in [0, 1) that depends on the ray (origin and direction) and the triangle:
// each ray decides on its own whether it goes through a hole.
double rayUniform(const RTCFilterFunctionNArguments* a, unsigned i, uint32_t face) {
    RTCRayN* r = a->ray;
    const unsigned n = a->N;
    uint64_t h = mix(face);
    for (float f : {RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i), RTCRayN_org_z(r, n, i), RTCRayN_dir_x(r, n, i),
                    RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i)})
        h = mix(h ^ bitsOf(f));
    return double(h >> 11) * (1.0 / 9007199254740992.0);
}

void surfaceFilter(const RTCFilterFunctionNArguments* a) {
    const SurfaceMesh& s = *static_cast<const SurfaceMesh*>(a->geometryUserPtr);
    for (unsigned i = 0; i < a->N; ++i) {
        if (a->valid[i] != -1) continue;
        const uint32_t face = RTCHitN_primID(a->hit, a->N, i);
        const glm::dvec2 uv = s.uvAt(face, RTCHitN_u(a->hit, a->N, i), RTCHitN_v(a->hit, a->N, i));
        if (!s.texture->scattering()) {  // MASK
            if (s.texture->coverage(uv) < s.texture->alphaCutoff) a->valid[i] = 0;
            continue;
        }
        const glm::dvec3 toOrigin(-RTCRayN_dir_x(a->ray, a->N, i), -RTCRayN_dir_y(a->ray, a->N, i),
                                  -RTCRayN_dir_z(a->ray, a->N, i));
        const glm::vec3 org(RTCRayN_org_x(a->ray, a->N, i), RTCRayN_org_y(a->ray, a->N, i),
                            RTCRayN_org_z(a->ray, a->N, i));
        const int level = s.level(face, org, -glm::vec3(toOrigin), RTCRayN_tfar(a->ray, a->N, i));
        const double pass = s.texture->passThrough(uv, s.frame(face).toLocal(toOrigin), level);
        if (rayUniform(a, i, face) < pass) a->valid[i] = 0;
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

const SurfaceScattering* SurfaceTexture::scattering() const {
    return bake && !bake->scattering.empty() ? &bake->scattering : nullptr;
}

namespace {

// A triangle's counter-clockwise normal (not normalized) and dP/du, dP/dv from its edges and
// their uv differences (det: of the uv edges; dP/du, dP/dv are not finite when it is 0).
struct UvTangents {
    glm::dvec3 normal, dPdu, dPdv;
    double det = 0;
};

UvTangents uvTangents(const BaseMesh& mesh, uint32_t face) {
    const glm::uvec3 f = mesh.faces[face], t = mesh.faceUvs[face];
    const glm::dvec3 e1 = mesh.positions[f.y] - mesh.positions[f.x], e2 = mesh.positions[f.z] - mesh.positions[f.x];
    const glm::dvec2 d1 = mesh.uvs[t.y] - mesh.uvs[t.x], d2 = mesh.uvs[t.z] - mesh.uvs[t.x];
    UvTangents d;
    d.normal = glm::cross(e1, e2);
    d.det = d1.x * d2.y - d2.x * d1.y;
    d.dPdu = (e1 * d2.y - e2 * d1.y) / d.det, d.dPdv = (e2 * d1.x - e1 * d2.x) / d.det;
    return d;
}

// The texel of `level` at uv (its texels cover 2^level x 2^level of level 0's, from the top left).
size_t levelTexel(const SurfaceTexture& t, const SurfaceTexture::Level& l, int level, glm::dvec2 uv) {
    const double s = fraction(uv.x * t.repeats.x), r = fraction(1.0 - uv.y * t.repeats.y);
    const int col = std::clamp(int(s * t.bake->width) >> level, 0, l.width - 1);
    const int row = std::clamp(int(r * t.bake->height) >> level, 0, l.height - 1);
    return size_t(row) * size_t(l.width) + size_t(col);
}

// Level k of the pyramid from level 0: texel (x, y) averages level 0's texels
// [x 2^k, (x + 1) 2^k) x [y 2^k, (y + 1) 2^k), clipped to the image (what levelTexel reads), the
// tint weighted by level 0's `coverage`.
SurfaceTexture::Level pyramidLevel(const SurfaceTexture::Level& base, const std::vector<float>& coverage, int k) {
    SurfaceTexture::Level n;
    const int step = 1 << k;
    n.width = (base.width + step - 1) / step, n.height = (base.height + step - 1) / step;
    n.tint.assign(size_t(3) * n.width * n.height, 1.f);
    n.holes.assign(size_t(n.width) * n.height, 0.f);
    for (int y = 0; y < n.height; ++y)
        for (int x = 0; x < n.width; ++x) {
            Rgb tint(0.0);
            double weight = 0, holes = 0;
            int count = 0;
            for (int r = y * step; r < std::min(base.height, (y + 1) * step); ++r)
                for (int c = x * step; c < std::min(base.width, (x + 1) * step); ++c) {
                    const size_t i = size_t(r) * base.width + c;
                    tint += double(coverage[i]) * Rgb(base.tint[3 * i], base.tint[3 * i + 1], base.tint[3 * i + 2]);
                    weight += coverage[i], holes += base.holes[i];
                    ++count;
                }
            const size_t o = size_t(y) * n.width + x;
            // The tint a hit sees: hits land where the yarn covers, so the covered texels weigh.
            if (weight > 0)
                for (int c = 0; c < 3; ++c) n.tint[3 * o + c] = float(tint[c] / weight);
            n.holes[o] = float(holes / count);
        }
    return n;
}

}  // namespace

Rgb SurfaceTexture::tint(glm::dvec2 uv, int level) const {
    if (!levels.empty()) {
        const int k = std::clamp(level, 0, maxLevel());
        const size_t i = levelTexel(*this, levels[size_t(k)], k, uv);
        const std::vector<float>& t = levels[size_t(k)].tint;
        return Rgb(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    }
    const Rgb a = albedo(uv);
    Rgb t(1.0);
    for (int c = 0; c < 3; ++c)
        if (meanAlbedo[c] > 0) t[c] = a[c] / meanAlbedo[c];
    return t;
}

double SurfaceTexture::passThrough(glm::dvec2 uv, const glm::dvec3& out, int level) const {
    const double pass = bake->scattering.passAt(out);
    if (!(meanHoles > 1e-6)) return pass;
    if (!levels.empty()) {
        const int k = std::clamp(level, 0, maxLevel());
        return std::clamp(pass * levels[size_t(k)].holes[levelTexel(*this, levels[size_t(k)], k, uv)], 0.0, 1.0);
    }
    return std::clamp(pass * (1.0 - coverage(uv)) / meanHoles, 0.0, 1.0);
}

SurfaceTexture makeSurfaceTexture(const SurfaceBake& bake, glm::dvec2 repeats) {
    SurfaceTexture t;
    t.bake = &bake;
    t.repeats = repeats;
    Rgb sum(0.0);
    double weight = 0;
    for (size_t i = 0; i < bake.coverage.size(); ++i) {
        sum += double(bake.coverage[i]) * Rgb(bake.albedo[3 * i], bake.albedo[3 * i + 1], bake.albedo[3 * i + 2]);
        weight += bake.coverage[i];
    }
    t.meanAlbedo = weight > 0 ? sum / weight : Rgb(0.0);
    t.meanHoles = 1.0 - bake.meanCoverage();
    // The pyramid of the tint and the holes (only a table reads them).
    if (!bake.scattering.empty() && bake.width > 0 && bake.height > 0) {
        SurfaceTexture::Level base;
        base.width = bake.width, base.height = bake.height;
        base.tint.resize(3 * bake.coverage.size());
        base.holes.resize(bake.coverage.size());
        for (size_t i = 0; i < bake.coverage.size(); ++i) {
            for (int c = 0; c < 3; ++c)
                base.tint[3 * i + c] = t.meanAlbedo[c] > 0 ? float(bake.albedo[3 * i + c] / t.meanAlbedo[c]) : 1.f;
            base.holes[i] = t.meanHoles > 1e-6 ? float((1.0 - bake.coverage[i]) / t.meanHoles) : 0.f;
        }
        t.levels.push_back(std::move(base));
        for (int k = 1; t.levels.back().width > 1 || t.levels.back().height > 1; ++k)
            t.levels.push_back(pyramidLevel(t.levels.front(), bake.coverage, k));
    }
    return t;
}

glm::dvec2 SurfaceMesh::uvAt(uint32_t face, float u, float v) const {
    const glm::uvec3 t = mesh->faceUvs[face];
    return (1.0 - double(u) - double(v)) * mesh->uvs[t.x] + double(u) * mesh->uvs[t.y] + double(v) * mesh->uvs[t.z];
}

int SurfaceMesh::level(uint32_t face, const glm::vec3& org, const glm::vec3& dir, float t) const {
    if (texture == nullptr || !(texture->pixelAngle > 0) || texture->levels.size() < 2) return 0;
    if (glm::length(org - texture->eye) > 1e-2f * std::max(1.f, glm::length(texture->eye)))
        return 0;  // not a camera ray
    // The footprint (metres, foreshortened) over the period's size on this triangle, in texels.
    const UvTangents d = uvTangents(*mesh, face);
    if (!(std::abs(d.det) > 0)) return 0;
    const double texelU = glm::length(d.dPdu) / (texture->repeats.x * texture->bake->width);
    const double texelV = glm::length(d.dPdv) / (texture->repeats.y * texture->bake->height);
    const double cosine = std::max(0.2, std::abs(glm::dot(glm::normalize(d.normal), glm::normalize(glm::dvec3(dir)))));
    const double footprint = double(t) * unit * texture->pixelAngle / cosine;
    const double texels = footprint / std::max(texelU, texelV);
    if (!(texels >= 2)) return 0;
    return int(std::min(std::floor(std::log2(texels)), double(texture->maxLevel())));  // inf: the top
}

ShadingFrame SurfaceMesh::frame(uint32_t face) const {
    const UvTangents d = uvTangents(*mesh, face);
    ShadingFrame fr;
    fr.z = glm::length(d.normal) > 0 ? glm::normalize(d.normal) : glm::dvec3(0, 0, 1);
    glm::dvec3 x = d.dPdu - glm::dot(d.dPdu, fr.z) * fr.z;
    if (!(std::abs(d.det) > 0) || !(glm::length(x) > 1e-12 * glm::length(d.dPdu)) || !std::isfinite(x.x))
        x = glm::cross(std::abs(fr.z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), fr.z);
    fr.x = glm::normalize(x);
    fr.y = glm::cross(fr.z, fr.x);
    if (std::abs(d.det) > 0 && glm::dot(fr.y, d.dPdv) < 0) fr.y = -fr.y;  // a mirrored uv layout
    return fr;
}

void setSurfaceFilter(RTCGeometry geometry, const SurfaceMesh& surface) {
    rtcSetGeometryUserData(geometry, const_cast<SurfaceMesh*>(&surface));
    rtcSetGeometryIntersectFilterFunction(geometry, surfaceFilter);
    rtcSetGeometryOccludedFilterFunction(geometry, surfaceFilter);
}

namespace impl {

PlyGeometry surfaceFrame(const Scene& scene, const glm::dvec3& centre) {
    PlyGeometry g;
    g.origin = centre;
    g.unit = scene.yarnRadius() > 0 ? scene.yarnRadius() : 1e-3;
    g.radius = 1.f;
    return g;
}

SurfaceTexture surfaceTexture(const Scene& scene, const RenderOptions& options) {
    if (!options.surface) return SurfaceTexture{};
    return makeSurfaceTexture(*options.surface, options.surfaceRepeats[0] > 0 && options.surfaceRepeats[1] > 0
                                                    ? glm::dvec2(options.surfaceRepeats[0], options.surfaceRepeats[1])
                                                    : scene.placement().repeats);
}

std::vector<ScatteringFocus> scatteringFocus(const BaseMesh& mesh, const glm::dvec3& eye, const glm::dvec3& light,
                                             size_t maxTriangles) {
    std::vector<ScatteringFocus> focus;
    const size_t faces = mesh.faces.size();
    if (faces == 0 || mesh.faceUvs.size() != faces) return focus;
    const size_t stride = std::max<size_t>(1, (faces + maxTriangles - 1) / std::max<size_t>(1, maxTriangles));
    const SurfaceMesh surface{&mesh, nullptr};
    focus.reserve(2 * (faces / stride + 1));
    for (size_t f = 0; f < faces; f += stride) {
        const glm::uvec3 t = mesh.faces[f];
        const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        const glm::dvec3 centre = (a + b + c) / 3.0, toEye = eye - centre, toLight = light - centre;
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a)), d2 = glm::dot(toEye, toEye);
        if (!(area > 0) || !(d2 > 0) || !(glm::dot(toLight, toLight) > 0)) continue;
        const ShadingFrame frame = surface.frame(uint32_t(f));
        const glm::dvec3 out = frame.toLocal(toEye / std::sqrt(d2));
        const double weight = area * std::abs(out.z) / d2;
        if (!(weight > 0)) continue;
        focus.push_back({out, weight});
        focus.push_back({frame.toLocal(glm::normalize(toLight)), weight});
    }
    return focus;
}

}  // namespace impl

}  // namespace knit
