// bakeSurface: the plies around one pattern cell, traced straight down with Embree; per pixel the
// coverage, height, normal and albedo of the first hits of stratified sub-pixel rays.
#include "knit/bake.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake_plies.hpp"
#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/ply_geometry.hpp"
#include "trace_scene.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

void requireRange(int value, int lo, int hi, const char* name) {
    if (value < lo || value > hi)
        throw Error(std::string("bake: ") + name + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) +
                    " (got " + std::to_string(value) + ")");
}

void validateBake(const Pattern& pattern, const BakeOptions& o) {
    requireRange(o.width, 1, 8192, "width (--bake-size)");
    requireRange(o.samplesPerAxis, 1, 64, "samplesPerAxis");
    requireRange(o.albedoPaths, 0, 1024, "albedoPaths");
    requireRange(o.maxBounces, 1, 64, "maxBounces");
    for (double v : o.origin)
        if (!(v >= 0 && v < 1)) throw Error("bake: origin must be in [0, 1) periods (got " + std::to_string(v) + ")");
    validatePattern(pattern, pattern.name.empty() ? "bake pattern" : pattern.name);
    validateMaterial(o.material, "bake material");
}

// Small counter-based random numbers: one stream per (pixel, sample), independent of threads.
struct Random {
    uint64_t state;
    double uniform() {
        state += 0x9E3779B97F4A7C15ull;
        uint64_t x = state;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return double((x ^ (x >> 31)) >> 11) * (1.0 / 9007199254740992.0);
    }
};

// What one pixel's sub-pixel rays saw.
struct PixelSum {
    int hits = 0;
    double height = 0;
    glm::dvec3 normal{0.0};
    Rgb albedo{0.0};
    Rgb transmittance{0.0};
    int albedoSamples = 0;
};

class Baker {
public:
    Baker(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables, const BakeOptions& o)
        : scene_(scene), plies_(scene.plies()), material_(material), tables_(tables), o_(o) {}

    // One stratified sample at pattern point (x, y): first hit straight down, then albedo paths.
    void sample(double x, double y, Random& rng, PixelSum& sum) const {
        const glm::vec3 org = plies_.toScene(glm::dvec3(x, y, top_));
        const glm::vec3 down(0, 0, -1);
        TraceHit h;
        if (!scene_.intersect(org, down, 0.f, kInf, h)) return;
        const glm::vec3 p = org + h.t * down;
        ++sum.hits;
        sum.height += plies_.toWorld(p).z;
        sum.normal += glm::dvec3(h.ng);
        for (int k = 0; k < o_.albedoPaths; ++k) skyPath(h, p, rng, sum), ++sum.albedoSamples;
    }

    double top_ = 0;  // ray origins' height (metres), above every yarn

private:
    ShadingFrame frameAt(const TraceHit& h) const {
        const uint32_t j = plies_.segments[h.segment];
        const float u = h.u;
        PlySurfacePoint sp;
        sp.tangent = glm::dvec3(glm::vec3(plies_.points[j + 1]) - glm::vec3(plies_.points[j]));
        sp.normal = glm::dvec3(h.ng);
        sp.radial = glm::dvec3((1 - u) * plies_.radial[j] + u * plies_.radial[j + 1]);
        sp.v = (1 - u) * plies_.arc[j] + u * plies_.arc[j + 1];
        return plyShadingFrame(sp, material_, tables_);
    }

    // One BSDF-sampled path (at most maxBounces bounces) of the radiance hit h sends straight up,
    // under a uniform white sky: the path's weight goes to the albedo when it escapes upwards (the
    // sky above the cloth, z > 0) and to the transmittance when it escapes downwards (the sky
    // below). The two skies are lit separately, so each is the estimate under its own sky alone.
    void skyPath(TraceHit h, glm::vec3 p, Random& rng, PixelSum& sum) const {
        Rgb beta(1.0);
        glm::vec3 d(0, 0, -1);
        for (int bounce = 0; bounce < o_.maxBounces; ++bounce) {
            const ShadingFrame frame = frameAt(h);
            const glm::dvec3 woL = frame.toLocal(-glm::dvec3(d));
            if ((glm::dot(-d, h.ng) > 0) != (woL.z > 0)) return;
            const PlyBsdf bsdf(material_, frame.shadow);
            const BsdfSample bs = bsdf.sample(woL, rng.uniform(), glm::dvec2(rng.uniform(), rng.uniform()));
            if (!bs.valid) return;
            const glm::vec3 wi = glm::normalize(glm::vec3(frame.toWorld(bs.wi)));
            if ((glm::dot(wi, h.ng) > 0) != (bs.wi.z > 0)) return;
            beta *= bs.weight;
            const glm::vec3 o = scene_.spawn(h, p, wi);
            TraceHit next;
            if (!scene_.intersect(o, wi, 0.f, kInf, next, &h)) {
                (wi.z > 0 ? sum.albedo : sum.transmittance) += beta;
                return;
            }
            p = o + next.t * wi, d = wi, h = next;
        }
    }

    const TraceScene& scene_;
    const PlyGeometry& plies_;
    const PlyMaterial& material_;
    const FiberTables& tables_;
    const BakeOptions& o_;
};

void storePixel(SurfaceBake& bake, size_t pixel, const PixelSum& s, int samples) {
    bake.coverage[pixel] = float(s.hits) / float(samples);
    if (s.hits == 0) return;
    const double h = (s.height / s.hits - bake.heightMin) / (bake.heightMax - bake.heightMin);
    bake.heights[pixel] = float(std::clamp(h, 0.0, 1.0));
    const glm::dvec3 n = glm::length(s.normal) > 0 ? glm::normalize(s.normal) : glm::dvec3(0, 0, 1);
    // Reflected plus transmitted light stays at most the light that came in, per channel (a few
    // paths' BSDF weights may add up beyond it): the surface level then conserves energy.
    const double paths = std::max(1, s.albedoSamples);
    Rgb a = glm::clamp(s.albedo / paths, 0.0, 1.0), t = glm::clamp(s.transmittance / paths, 0.0, 1.0);
    for (int c = 0; c < 3; ++c)
        if (a[c] + t[c] > 1) {
            const double scale = 1 / (a[c] + t[c]);
            a[c] *= scale, t[c] *= scale;
        }
    for (int c = 0; c < 3; ++c) {
        bake.normal[3 * pixel + c] = float(n[c]), bake.albedo[3 * pixel + c] = float(a[c]);
        bake.transmittance[3 * pixel + c] = float(t[c]);
    }
}

// Pixels without any hit take the coverage-weighted mean colour (of `rgb`: the albedo or the
// transmittance), so filtering across a hole edge does not darken the yarn's border.
void fillUncovered(const std::vector<float>& coverage, std::vector<float>& rgb) {
    Rgb sum(0.0);
    double weight = 0;
    const size_t n = coverage.size();
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) sum[c] += coverage[i] * rgb[3 * i + c];
    for (size_t i = 0; i < n; ++i) weight += coverage[i];
    const Rgb mean = weight > 0 ? sum / weight : Rgb(0.0);
    for (size_t i = 0; i < n; ++i)
        if (coverage[i] == 0.f)
            for (int c = 0; c < 3; ++c) rgb[3 * i + c] = float(mean[c]);
}

}  // namespace

double SurfaceBake::meanCoverage() const {
    double s = 0;
    for (float c : coverage) s += c;
    return coverage.empty() ? 0.0 : s / double(coverage.size());
}

SurfaceBake bakeSurface(const Pattern& pattern, const BakeOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    // Step 1: validate, then the periodic plies around the cell.
    validateBake(pattern, o);
    const BakePlies bp = bakePlies(pattern, o.plies, o.periodicPitch);
    SurfaceBake bake;
    bake.width = o.width;
    bake.height = std::max(1, int(std::lround(o.width * pattern.py / pattern.px)));
    bake.period[0] = pattern.px, bake.period[1] = pattern.py;
    bake.heightMin = bp.zMin, bake.heightMax = bp.zMax;
    bake.yarnPitch = bp.yarnPitch;
    // Step 2: the Embree scene (round curves) and the fiber tables of the material.
    int plyCount = 1;
    for (uint8_t p : bp.plies.plyOfCurve) plyCount = std::max(plyCount, int(p) + 1);
    const FiberTables tables = buildFiberTables(fiberTableOptions(o.material, plyCount));
    const PlyGeometry geometry =
        buildPlyGeometry(bp.plies, glm::dvec3(0.5 * pattern.px, 0.5 * pattern.py, 0.0), o.material.fiberTwist);
    bake.plySegments = geometry.segmentCount();
    EmbreeDevice device;
    TraceSceneOptions so;
    so.mode = GeometryMode::Curves;
    const TraceScene scene(device, geometry, so);
    Baker baker(scene, o.material, tables, o);
    baker.top_ = bp.zMax + 2 * bp.yarnRadius;
    // Step 3: per pixel, s x s stratified rays at periodic positions (pixel centres (i + 0.5) / N).
    const size_t pixels = size_t(bake.width) * size_t(bake.height);
    bake.albedo.assign(3 * pixels, 0.f), bake.normal.assign(3 * pixels, 0.f), bake.heights.assign(pixels, 0.f);
    bake.transmittance.assign(3 * pixels, 0.f);
    bake.coverage.assign(pixels, 0.f);
    for (size_t i = 0; i < pixels; ++i) bake.normal[3 * i + 2] = 1.f;
    const int s = o.samplesPerAxis;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t pixel = r.begin(); pixel != r.end(); ++pixel) {
            const int col = int(pixel % size_t(bake.width)), row = int(pixel / size_t(bake.width));
            PixelSum sum;
            for (int k = 0; k < s * s; ++k) {
                Random rng{o.seed * 0x100000001B3ull + pixel * 4096 + size_t(k)};
                const double a = (k % s + 0.5) / s, b = (k / s + 0.5) / s;
                baker.sample((o.origin[0] + (col + a) / bake.width) * pattern.px,
                             (o.origin[1] + 1.0 - (row + b) / bake.height) * pattern.py, rng, sum);
            }
            storePixel(bake, pixel, sum, s * s);
        }
    });
    fillUncovered(bake.coverage, bake.albedo);
    fillUncovered(bake.coverage, bake.transmittance);
    bake.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bake;
}

namespace {
uint8_t toByte(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }
double linearToSrgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }
}  // namespace

std::vector<uint8_t> baseColorRgba8(const SurfaceBake& bake) {
    std::vector<uint8_t> out(4 * bake.coverage.size());
    for (size_t i = 0; i < bake.coverage.size(); ++i) {
        for (int c = 0; c < 3; ++c) out[4 * i + c] = toByte(linearToSrgb(bake.albedo[3 * i + c]));
        out[4 * i + 3] = toByte(bake.coverage[i]);
    }
    return out;
}

std::vector<uint8_t> normalRgb8(const SurfaceBake& bake) {
    std::vector<uint8_t> out(bake.normal.size());
    for (size_t i = 0; i < bake.normal.size(); ++i) out[i] = toByte(0.5 * (bake.normal[i] + 1.0));
    return out;
}

std::vector<uint8_t> heightGray8(const SurfaceBake& bake) {
    std::vector<uint8_t> out(bake.heights.size());
    for (size_t i = 0; i < bake.heights.size(); ++i) out[i] = toByte(bake.heights[i]);
    return out;
}

PlyOptions patternPlyOptions(PlyOptions plies, const Pattern& pattern, double scale) {
    plies.yarnRadius = pattern.radius;
    plies.pitch /= scale, plies.centerRadius /= scale, plies.plyRadius /= scale;
    return plies;
}

}  // namespace knit
