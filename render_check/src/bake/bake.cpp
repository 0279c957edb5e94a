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
#include "bake_scattering.hpp"
#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/ply_geometry.hpp"
#include "tracing/trace_scene.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kScatteringMargin = 1;  // tiles beyond the texture bake's on every side

void requireRange(int value, int lo, int hi, const char* name) {
    if (value < lo || value > hi)
        throw Error(std::string("bake: ") + name + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) +
                    " (got " + std::to_string(value) + ")");
}

void validateBake(const Pattern& pattern, const BakeOptions& o) {
    requireRange(o.width, 1, 8192, "the bake size");
    requireRange(o.samplesPerAxis, 1, 64, "samplesPerAxis");
    requireRange(o.albedoPaths, 0, 1024, "albedoPaths");
    requireRange(o.maxBounces, 1, 64, "maxBounces");
    requireRange(o.scatteringPaths, 0, 1 << 20, "the scattering paths");
    requireRange(o.scatteringSide, 1, 32, "scatteringSide");  // 2048 bins: a 50 MB table
    if (!(o.scatteringFocusShare >= 0 && o.scatteringFocusShare <= 1))
        throw Error("bake: scatteringFocusShare must be in [0, 1] (got " + std::to_string(o.scatteringFocusShare) +
                    ")");
    for (double v : o.origin)
        if (!(v >= 0 && v < 1)) throw Error("bake: origin must be in [0, 1) periods (got " + std::to_string(v) + ")");
    for (double v : o.stretch)
        if (!(v > 0 && v < 1e3)) throw Error("bake: stretch must be positive (got " + std::to_string(v) + ")");
    validatePattern(pattern, pattern.name.empty() ? "bake pattern" : pattern.name);
    validateMaterial(o.material, "bake material");
}

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
    Baker(const PlyPaths& paths, const BakeOptions& o) : paths_(paths), plies_(paths.scene().plies()), o_(o) {}

    // One stratified sample at pattern point (x, y): first hit straight down, then albedo paths.
    void sample(double x, double y, BakeRandom& rng, PixelSum& sum) const {
        const glm::vec3 org = plies_.toScene(glm::dvec3(x, y, top_));
        const glm::vec3 down(0, 0, -1);
        TraceHit h;
        if (!paths_.scene().intersect(org, down, 0.f, kInf, h)) return;
        const glm::vec3 p = org + h.t * down;
        ++sum.hits;
        sum.height += plies_.toWorld(p).z;
        sum.normal += glm::dvec3(h.ng);
        // Under a uniform white sky: a path's weight goes to the albedo when it escapes upwards
        // (the sky above the cloth, z > 0) and to the transmittance when it escapes downwards
        // (the sky below). The two skies are lit separately, so each is the estimate under its
        // own sky alone.
        for (int k = 0; k < o_.albedoPaths; ++k, ++sum.albedoSamples) {
            const Escape e = paths_.follow(h, p, down, rng, o_.maxBounces);
            if (e.escaped) (e.direction.z > 0 ? sum.albedo : sum.transmittance) += e.weight;
        }
    }

    double top_ = 0;  // ray origins' height (metres), above every yarn

private:
    const PlyPaths& paths_;
    const PlyGeometry& plies_;
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

namespace {
// The pattern as the placement lays it on the mesh: x and y stretched, heights and radius kept.
Pattern stretchedPattern(const Pattern& pattern, const double stretch[2]) {
    Pattern p = pattern;
    for (glm::dvec3& q : p.points) q.x *= stretch[0], q.y *= stretch[1];
    p.px *= stretch[0], p.py *= stretch[1];
    return p;
}
}  // namespace

SurfaceBake bakeSurface(const Pattern& original, const BakeOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    // Step 1: validate, then the periodic plies around the cell (of the pattern as placed).
    validateBake(original, o);
    const Pattern pattern = stretchedPattern(original, o.stretch);
    // A scattering table needs more tiles around the cell: its oblique rays cross several.
    const int margin = o.scatteringPaths > 0 ? kScatteringMargin : 0;
    const BakePlies bp = bakePlies(pattern, o.plies, o.periodicPitch, margin);
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
    PeriodicCloth cloth;
    cloth.period = glm::dvec2(pattern.px, pattern.py);
    cloth.centre = (glm::dvec2(o.origin[0], o.origin[1]) + 0.5) * cloth.period;
    cloth.zTop = bp.zMax + 2 * bp.yarnRadius, cloth.zBottom = bp.zMin - 2 * bp.yarnRadius;
    cloth.reach = 0.5 + margin;  // within the tiles around the cell
    const PlyPaths paths(scene, o.material, tables, cloth);
    Baker baker(paths, o);
    baker.top_ = cloth.zTop;
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
                BakeRandom rng{o.seed * 0x100000001B3ull + pixel * 4096 + size_t(k)};
                const double a = (k % s + 0.5) / s, b = (k / s + 0.5) / s;
                baker.sample((o.origin[0] + (col + a) / bake.width) * pattern.px,
                             (o.origin[1] + 1.0 - (row + b) / bake.height) * pattern.py, rng, sum);
            }
            storePixel(bake, pixel, sum, s * s);
        }
    });
    fillUncovered(bake.coverage, bake.albedo);
    fillUncovered(bake.coverage, bake.transmittance);
    // Step 4: the scattering table of the cell seen as a surface (optional).
    if (o.scatteringPaths > 0) {
        ScatteringSetup ss;
        ss.cellMin = glm::dvec2(o.origin[0] * pattern.px, o.origin[1] * pattern.py);
        ss.cellSize = glm::dvec2(pattern.px, pattern.py);
        ss.zTop = cloth.zTop, ss.zBottom = cloth.zBottom;
        ss.pathsPerBin = o.scatteringPaths;
        ss.side = o.scatteringSide;
        SurfaceScattering layout;
        layout.side = ss.side;
        if (!o.scatteringFocus.empty())
            ss.pathsOfBin = focusedPaths(layout, ss.pathsPerBin, o.scatteringFocus, o.scatteringFocusShare);
        ss.maxBounces = std::max(o.maxBounces, 8);
        ss.seed = o.seed;
        bake.scattering = measureScattering(paths, ss);
    }
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

glm::dvec2 placementStretch(const Pattern& pattern, const PatternPlacement& placement) {
    const double sx = placement.periodMetres.x / pattern.px, sy = placement.periodMetres.y / pattern.py;
    const double scale = std::sqrt(sx * sy);
    if (!(scale > 0) || !std::isfinite(scale)) return glm::dvec2(1.0);
    return glm::dvec2(sx / scale, sy / scale);
}

PlyOptions patternPlyOptions(PlyOptions plies, const Pattern& pattern, double scale) {
    plies.yarnRadius = pattern.radius;
    plies.pitch /= scale, plies.centerRadius /= scale, plies.plyRadius /= scale;
    return plies;
}

}  // namespace knit
