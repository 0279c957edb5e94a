// measureScattering: the scattering table of a pattern cell, from paths through its flat plies.
#include "bake_scattering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/error.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// What the paths of one out bin saw.
struct BinSum {
    std::vector<Rgb> in;  // per in bin
    size_t passed = 0;
};

// Reciprocity: f(in, out) = table(out, in) / (|cos in| solid angle) equals f(out, in); the two
// independent estimates (from the paths of row out and of row in) are averaged, each weighted by
// its row's path count.
void symmetrize(SurfaceScattering& s, const std::vector<int>& paths) {
    const int n = s.bins();
    std::vector<double> cosine(size_t(n), 0.0);
    for (int b = 0; b < n; ++b) cosine[size_t(b)] = s.binCosine(b);
    for (int o = 0; o < n; ++o)
        for (int i = o + 1; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                float& a = s.table[3 * (size_t(o) * n + i) + c];  // in = i, out = o
                float& b = s.table[3 * (size_t(i) * n + o) + c];  // in = o, out = i
                const double ci = cosine[size_t(i)], co = cosine[size_t(o)];
                // Weighted by the rows' paths. (Also weighting by the cosine each estimate is divided
                // by, its variance model, made the far garment view worse: 3.29% -> 3.40%.)
                const double wa = paths[size_t(o)], wb = paths[size_t(i)];
                const double f = (wa * a / ci + wb * b / co) / (wa + wb);
                a = float(f * ci), b = float(f * co);
            }
}

}  // namespace

double BakeRandom::uniform() {
    state += 0x9E3779B97F4A7C15ull;
    uint64_t x = state;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return double((x ^ (x >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}

PlyPaths::PlyPaths(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables,
                   const PeriodicCloth& cloth)
    : scene_(scene), material_(material), tables_(tables) {
    const PlyGeometry& g = scene.plies();
    period_ = glm::vec2(cloth.period / g.unit);
    centre_ = glm::vec2(g.toScene(glm::dvec3(cloth.centre, 0.0)));
    zTop_ = g.toScene(glm::dvec3(0, 0, cloth.zTop)).z, zBottom_ = g.toScene(glm::dvec3(0, 0, cloth.zBottom)).z;
    step_ = float(cloth.reach * std::min(cloth.period.x, cloth.period.y) / g.unit);
}

bool PlyPaths::intersect(glm::vec3 o, const glm::vec3& d, TraceHit& hit, glm::vec3& p, const TraceHit* from) const {
    const float across = std::sqrt(d.x * d.x + d.y * d.y);
    for (int piece = 0; piece < 100000; ++piece) {
        // Step 1: how far the ray may go: out of the layer, or `step_` sideways.
        float tLayer = kInf;
        if (d.z > 0) tLayer = std::max(0.f, (zTop_ - o.z) / d.z);
        if (d.z < 0) tLayer = std::max(0.f, (zBottom_ - o.z) / d.z);
        const float tSide = across > 0 ? step_ / across : kInf;
        const float tFar = std::min(tLayer, tSide);
        // Step 2: a hit in that piece, or out of the layer, or on from a copy nearer the cell.
        if (scene_.intersect(o, d, 0.f, tFar == kInf ? kInf : tFar, hit, piece == 0 ? from : nullptr)) {
            p = o + hit.t * d;
            return true;
        }
        if (tFar == tLayer) return false;
        o += tFar * d;
        const glm::vec2 shift = glm::round((glm::vec2(o) - centre_) / period_) * period_;
        o.x -= shift.x, o.y -= shift.y;
    }
    return false;
}

Escape PlyPaths::follow(TraceHit h, glm::vec3 p, glm::vec3 d, BakeRandom& rng, int maxBounces) const {
    Escape e;
    Rgb beta(1.0);
    for (int bounce = 0; bounce < maxBounces; ++bounce) {
        const ShadingFrame frame = plyShadingFrame(scene_.plyPoint(h), material_, tables_);
        const glm::dvec3 woL = frame.toLocal(-glm::dvec3(d));
        if ((glm::dot(-d, h.ng) > 0) != (woL.z > 0)) return e;
        const PlyBsdf bsdf(material_, frame.shadow);
        // The three numbers drawn in a set order (a braced list is sequenced; call arguments are not,
        // so the image for a seed would depend on the compiler).
        const double u[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
        const BsdfSample bs = bsdf.sample(woL, u[0], glm::dvec2(u[1], u[2]));
        if (!bs.valid) return e;
        const glm::vec3 wi = glm::normalize(glm::vec3(frame.toWorld(bs.wi)));
        if ((glm::dot(wi, h.ng) > 0) != (bs.wi.z > 0)) return e;
        beta *= bs.weight;
        const glm::vec3 o = scene_.spawn(h, p, wi);
        TraceHit next;
        glm::vec3 q;
        if (!intersect(o, wi, next, q, &h)) {
            e.escaped = true, e.direction = wi, e.weight = beta;
            return e;
        }
        p = q, d = wi, h = next;
    }
    return e;
}

std::vector<int> focusedPaths(const SurfaceScattering& layout, int pathsPerBin,
                              const std::vector<ScatteringFocus>& focus, double share) {
    const int n = layout.bins();
    std::vector<double> weight(size_t(n), 0.0);
    double total = 0;
    for (const ScatteringFocus& f : focus) {
        if (!(f.weight > 0) || !std::isfinite(f.weight) || !(glm::length(f.direction) > 0)) continue;
        int bins[4];
        double w[4];
        layout.interpolationCorners(f.direction, bins, w);
        for (int k = 0; k < 4; ++k) weight[size_t(bins[k])] += f.weight * w[k];
        total += f.weight;
    }
    if (!(total > 0)) share = 0;
    const double budget = double(pathsPerBin) * n;
    std::vector<int> paths(static_cast<size_t>(n));
    for (int b = 0; b < n; ++b) {
        const double count = (1 - share) * pathsPerBin + (total > 0 ? share * budget * weight[size_t(b)] / total : 0);
        paths[size_t(b)] = int(std::clamp(std::round(count), 1.0, double(1 << 30)));  // clamped before the cast
    }
    return paths;
}

SurfaceScattering measureScattering(const PlyPaths& paths, const ScatteringSetup& s) {
    SurfaceScattering out;
    out.side = s.side;
    const int n = out.bins();
    const std::vector<int> pathsOfBin =
        s.pathsOfBin.empty() ? std::vector<int>(size_t(n), s.pathsPerBin) : s.pathsOfBin;
    if (pathsOfBin.size() != size_t(n) || *std::min_element(pathsOfBin.begin(), pathsOfBin.end()) < 1)
        throw Error("bake: every direction bin needs at least one scattering path");
    out.table.assign(size_t(3) * n * n, 0.f);
    out.pass.assign(size_t(n), 0.f);
    const PlyGeometry& g = paths.scene().plies();
    // Step 1: per out bin (in parallel), its paths in order from its own random streams.
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& r) {
        for (int bin = r.begin(); bin != r.end(); ++bin) {
            BinSum sum;
            sum.in.assign(size_t(n), Rgb(0.0));
            const int count = pathsOfBin[size_t(bin)];
            for (int k = 0; k < count; ++k) {
                BakeRandom rng{s.seed * 0x2545F4914F6CDD1Dull + (uint64_t(bin) << 32) + uint64_t(k)};
                // Step 1a: a direction in the bin and an entry point on its side's plane.
                const double u = rng.uniform(), v = rng.uniform();
                const glm::dvec3 outDir = out.binDirection(bin, u, v);
                const double z = outDir.z;
                const glm::dvec3 entry(s.cellMin.x + rng.uniform() * s.cellSize.x,
                                       s.cellMin.y + rng.uniform() * s.cellSize.y, z >= 0 ? s.zTop : s.zBottom);
                const glm::vec3 org = g.toScene(entry), d = glm::vec3(-outDir);
                // Step 1b: through a hole, or scattered by the plies until it leaves them.
                TraceHit h;
                glm::vec3 p;
                if (!paths.intersect(org, d, h, p)) {
                    ++sum.passed;
                    continue;
                }
                const Escape e = paths.follow(h, p, d, rng, s.maxBounces);
                if (e.escaped) sum.in[size_t(out.binOf(glm::dvec3(e.direction)))] += e.weight;
            }
            // Step 1c: averages over the bin's paths.
            const double inv = 1.0 / count;
            out.pass[size_t(bin)] = float(sum.passed * inv);
            for (int b = 0; b < n; ++b)
                for (int c = 0; c < 3; ++c)
                    out.table[3 * (size_t(bin) * n + b) + c] = float(sum.in[size_t(b)][c] * inv);
        }
    });
    out.paths = 0;
    for (int c : pathsOfBin) out.paths += size_t(c);
    // Step 2: reciprocity (the ply BSDF is reciprocal, and so is the cloth's scattering): the
    // two estimates of each entry are averaged (symmetrize).
    symmetrize(out, pathsOfBin);
    // Step 3: the rows' sampling distributions.
    out.prepare();
    return out;
}

}  // namespace knit
