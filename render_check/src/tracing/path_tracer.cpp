// Path tracer: camera rays, NEE to the area light with MIS, the environment where a scattered ray
// escapes, sampling of the scattering at each hit (bsdf/scattering.hpp: ply BSDF, surface table or
// diffuse base mesh).
#include "knit/path_tracer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "knit/error.hpp"
#include "bsdf/scattering.hpp"
#include "knit/ply_bsdf.hpp"
#include "render_image.hpp"
#include "trace_scene.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

using util::kPi;
constexpr float kInf = std::numeric_limits<float>::infinity();

uint64_t splitmix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// PCG32 (O'Neill): small per-pixel stream.
struct Rng {
    uint64_t state, inc;
    Rng(uint64_t seed, uint64_t stream) : state(0), inc((stream << 1u) | 1u) {
        next();
        state += seed;
        next();
    }
    uint32_t next() {
        const uint64_t old = state;
        state = old * 6364136223846793005ull + inc;
        const uint32_t xs = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xs >> rot) | (xs << ((-rot) & 31));
    }
    double uniform() { return next() * (1.0 / 4294967296.0); }
};

// The points in a pixel of its spp samples: a jittered cols x rows grid of spp strata (cols the
// largest divisor of spp <= sqrt(spp)), visited in a random order per pixel. Each sample is uniform
// in the pixel on its own; together they cover the pixel evenly, which takes most of the noise out
// of the yarn's edges and highlights. Only the pixel is stratified: strata for the light point and
// the first scattering too lowered the close-up's noise a little more but made the material fit
// (knit/fit.hpp, whose renders share one seed across materials) miss its albedo on 2 of 4 seeds.
class PixelStrata {
public:
    explicit PixelStrata(int spp) : cols_(1), order_(size_t(spp)) {
        for (int c = 1; c * c <= spp; ++c)
            if (spp % c == 0) cols_ = c;
    }
    void shuffle(Rng& rng) {
        const uint32_t n = uint32_t(order_.size());
        for (uint32_t k = 0; k < n; ++k) order_[k] = k;
        for (uint32_t k = n - 1; k > 0; --k) std::swap(order_[k], order_[rng.next() % (k + 1)]);
    }
    // The point of sample k in the pixel, in [0, 1)^2.
    glm::dvec2 point(int k, Rng& rng) const {
        const uint32_t st = order_[size_t(k)];
        const int rows = int(order_.size()) / cols_;
        const double x = (int(st % cols_) + rng.uniform()) / cols_, y = (int(st / cols_) + rng.uniform()) / rows;
        return {x, y};
    }

private:
    int cols_;
    std::vector<uint32_t> order_;
};

double power(double a, double b) { return a * a / (a * a + b * b); }

struct LightGeom {
    glm::vec3 corner, eu, ev, n;  // relative to the scene origin
    double area = 0;
    Rgb radiance{0.0};
    bool on = false;
};

// Ray / light parallelogram: t > 0 or infinity; front = ray hits the emitting side.
float hitLight(const LightGeom& l, const glm::vec3& o, const glm::vec3& d, bool& front) {
    if (!l.on) return kInf;
    const float denom = glm::dot(d, l.n);
    if (std::abs(denom) < 1e-12f) return kInf;
    const float t = glm::dot(l.corner - o, l.n) / denom;
    if (!(t > 0)) return kInf;
    const glm::vec3 q = o + t * d - l.corner;
    const float a = glm::dot(q, l.eu) / glm::dot(l.eu, l.eu), b = glm::dot(q, l.ev) / glm::dot(l.ev, l.ev);
    if (a < 0 || a > 1 || b < 0 || b > 1) return kInf;
    front = denom < 0;
    return t;
}

// The frame at a hit and what scatters light there (bsdf/scattering.hpp).
struct Shading {
    ShadingFrame frame;
    impl::Scattering scattering;
};

struct Tracer {
    const TraceScene& scene;
    const PlyMaterial& material;
    const FiberTables& tables;
    const TraceSettings& s;
    LightGeom light;
    glm::vec3 eye, fwd, right, up;
    double tanHalf, aspect;
    bool env;
    uint64_t* rays;

    // o, d: the ray that found h (a camera ray reads the surface level's texture prefiltered).
    Shading shade(const TraceHit& h, const glm::vec3& o, const glm::vec3& d) const {
        if (h.kind == TraceHit::Base && scene.baseTexture() && scene.baseTexture()->scattering()) {
            // The surface level's table: the texel's tint over the probability of the hit, 1 - pass
            // (the surface filter).
            const ShadingFrame frame = scene.baseFrame(h);
            const SurfaceScattering* table = scene.baseTexture()->scattering();
            const Rgb tint = scene.baseTexture()->tint(scene.baseUv(h), scene.baseLevel(h, o, d));
            const glm::dvec3 woL = frame.toLocal(-glm::dvec3(d));
            return {frame, impl::TableScattering{table, tint / std::max(1e-6, 1.0 - table->passAt(woL))}};
        }
        if (h.kind == TraceHit::Base) {
            impl::DiffuseScattering diffuse;
            diffuse.albedo = scene.baseAlbedo(h, s.baseAlbedo);
            diffuse.transmit = scene.baseTransmittance(h);
            const double r = luminance(diffuse.albedo), t = luminance(diffuse.transmit);
            if (t > 0) diffuse.reflectChance = r / (r + t);
            ShadingFrame frame;
            frame.z = glm::dvec3(h.ng);
            const glm::dvec3 a = std::abs(frame.z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
            frame.x = glm::normalize(glm::cross(a, frame.z));
            frame.y = glm::cross(frame.z, frame.x);
            return {frame, diffuse};
        }
        const PlyGeometry& g = scene.plies();
        const uint32_t j = g.segments[h.segment];
        const float u = h.u;
        const ShadingFrame frame = plyShadingFrame(scene.plyPoint(h), material, tables);
        // A yarn colour (nearer end of the segment: colours change between stitches) tints the body.
        const Rgb body =
            g.colour.empty() ? material.bodyAlbedo : yarnBodyAlbedo(material, g.colour[u < 0.5f ? j : j + 1]);
        return {frame, impl::PlyScattering{PlyBsdf(material, frame.shadow, body)}};
    }

    // Scattering value (with |cos|) and pdf for world directions; zero when the shading and
    // geometric sides disagree.
    Rgb evalScattering(const Shading& sh, const glm::dvec3& woL, const glm::dvec3& wi, const glm::vec3& ng,
                       double& pdf) const {
        pdf = 0;
        const glm::dvec3 wiL = sh.frame.toLocal(wi);
        if ((glm::dot(glm::vec3(wi), ng) > 0) != (wiL.z > 0)) return Rgb(0.0);
        return sh.scattering.eval(woL, wiL, pdf);
    }

    Rgb radiance(glm::vec3 o, glm::vec3 d, Rng& rng) const {
        Rgb L(0.0), beta(1.0);
        double prevPdf = 0;
        TraceHit prev;
        for (int depth = 0;; ++depth) {
            TraceHit h;
            ++*rays;
            const bool hit = scene.intersect(o, d, 0.f, kInf, h, depth > 0 ? &prev : nullptr);
            // Step 1: emission from the light (MIS against the light samples) or the environment.
            bool front = false;
            const float tl = hitLight(light, o, d, front);
            if (front && tl < (hit ? h.t : kInf)) {  // the light's back is not there
                double w = 1;
                if (depth > 0) {
                    const float cosL = -glm::dot(d, light.n);
                    const double pdfL = double(tl) * tl / (light.area * cosL);
                    w = power(prevPdf, pdfL);
                }
                L += beta * light.radiance * w;
                break;
            }
            // The constant environment is found only by the paths' own scattered rays: sampling the
            // scattering already follows f |cos| (a Lambertian body's weight is its albedo whatever
            // the direction), while a shadow ray to a uniform direction of the sphere cost a
            // quarter of all rays and lowered the close-up's noise by less than it cost (docs/views.md).
            if (!hit) {
                if (env) L += beta * s.environment;
                break;
            }
            if (depth >= s.maxDepth) break;
            // Step 2: local frame and scattering at the hit.
            const glm::vec3 p = o + h.t * d;
            const Shading sh = shade(h, o, d);
            const glm::dvec3 wo = -glm::dvec3(d);
            const glm::dvec3 woL = sh.frame.toLocal(wo);
            if ((glm::dot(-d, h.ng) > 0) != (woL.z > 0)) break;
            // Step 3: next-event estimation to the area light.
            if (light.on) {
                const glm::vec3 y = light.corner + float(rng.uniform()) * light.eu + float(rng.uniform()) * light.ev;
                const glm::vec3 toL = y - p;
                const float dist = glm::length(toL);
                const glm::vec3 wi = toL / dist;
                const float cosL = -glm::dot(wi, light.n);
                if (cosL > 0) {
                    double pdfB;
                    const Rgb f = evalScattering(sh, woL, glm::dvec3(wi), h.ng, pdfB);
                    if (f != Rgb(0.0)) {
                        const glm::vec3 org = scene.spawn(h, p, wi);
                        const glm::vec3 seg = y - org;
                        const float len = glm::length(seg);
                        ++*rays;
                        if (!scene.occluded(org, seg / len, 0.f, len * (1 - 1e-4f), &h)) {
                            const double pdfL = double(dist) * dist / (light.area * cosL);
                            L += beta * f * light.radiance * (power(pdfL, pdfB) / pdfL);
                        }
                    }
                }
            }
            // Step 4: continue the path by sampling the scattering.
            const impl::ScatterSample next = sh.scattering.sample(woL, rng);
            if (!next.valid) break;
            const glm::vec3 wi = glm::normalize(glm::vec3(sh.frame.toWorld(next.wi)));
            if ((glm::dot(wi, h.ng) > 0) != (next.wi.z > 0)) break;
            beta *= next.weight;
            prevPdf = next.pdf;
            // Step 5: Russian roulette.
            if (depth >= 3) {
                const double q = std::min(0.95, std::max({beta.x, beta.y, beta.z}));
                if (rng.uniform() >= q) break;
                beta /= q;
            }
            o = scene.spawn(h, p, wi);
            d = wi;
            prev = h;
        }
        return L;
    }
};

}  // namespace

Rgb Image::pixel(int x, int y) const {
    const size_t i = 3 * (size_t(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

Rgb Image::mean() const {
    Rgb m(0.0);
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) m += Rgb(rgb[i], rgb[i + 1], rgb[i + 2]);
    return rgb.empty() ? m : m / double(rgb.size() / 3);
}

Image renderImage(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables,
                  const TraceSettings& s, TraceStats* stats) {
    if (s.width < 1 || s.height < 1) throw Error("cannot render: image size must be at least 1 x 1");
    if (s.spp < 1)
        throw Error("cannot render: samples per pixel must be at least 1 (got " + std::to_string(s.spp) + ")");
    const auto start = std::chrono::steady_clock::now();
    const PlyGeometry& g = scene.plies();
    Tracer tr{scene, material, tables, s, {}, {}, {}, {}, {}, 0, 0, false, nullptr};
    // Step 1: camera basis and light in scene units (uniform scaling leaves radiance unchanged).
    tr.eye = g.toScene(s.camera.eye);
    const glm::dvec3 fwd = glm::normalize(s.camera.target - s.camera.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, s.camera.up));
    tr.fwd = glm::vec3(fwd), tr.right = glm::vec3(right), tr.up = glm::vec3(glm::cross(right, fwd));
    tr.tanHalf = std::tan(s.camera.fovYDegrees * kPi / 360.0);
    tr.aspect = double(s.width) / s.height;
    const glm::dvec3 eu = s.light.edgeU / g.unit, ev = s.light.edgeV / g.unit;
    const glm::dvec3 ln = glm::cross(eu, ev);
    tr.light.area = glm::length(ln);
    tr.light.on = tr.light.area > 0 && (s.light.radiance.x > 0 || s.light.radiance.y > 0 || s.light.radiance.z > 0);
    if (tr.light.on) {
        tr.light.corner = g.toScene(s.light.corner);
        tr.light.eu = glm::vec3(eu), tr.light.ev = glm::vec3(ev);
        tr.light.n = glm::vec3(ln / tr.light.area);
        tr.light.radiance = s.light.radiance;
    }
    tr.env = s.environment.x > 0 || s.environment.y > 0 || s.environment.z > 0;
    // Step 2: tiles in parallel, one random stream per pixel.
    Image img;
    img.width = s.width, img.height = s.height;
    img.rgb.assign(size_t(3) * s.width * s.height, 0.f);
    img.variance.assign(size_t(s.width) * s.height, 0.f);
    const int tile = 16, tx = (s.width + tile - 1) / tile, ty = (s.height + tile - 1) / tile;
    tbb::combinable<uint64_t> rays([] { return uint64_t(0); });
    std::atomic<int> done{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, tx * ty, 1), [&](const tbb::blocked_range<int>& range) {
        uint64_t& localRays = rays.local();
        Tracer t = tr;
        t.rays = &localRays;
        PixelStrata strata(s.spp);
        for (int ti = range.begin(); ti < range.end(); ++ti) {
            const int x0 = (ti % tx) * tile, y0 = (ti / tx) * tile;
            for (int y = y0; y < std::min(s.height, y0 + tile); ++y)
                for (int x = x0; x < std::min(s.width, x0 + tile); ++x) {
                    const uint64_t index = uint64_t(y) * s.width + x;
                    Rng rng(splitmix(s.seed ^ splitmix(index)), splitmix(index + 0x1234567ull));
                    strata.shuffle(rng);
                    Rgb sum(0.0);
                    double lum = 0, lum2 = 0;
                    for (int k = 0; k < s.spp; ++k) {
                        const glm::dvec2 px = strata.point(k, rng);
                        const double sx = (2 * (x + px.x) / s.width - 1) * t.tanHalf * t.aspect;
                        const double sy = (1 - 2 * (y + px.y) / s.height) * t.tanHalf;
                        const glm::vec3 d = glm::normalize(t.fwd + float(sx) * t.right + float(sy) * t.up);
                        Rgb L = t.radiance(t.eye, d, rng);
                        if (!std::isfinite(L.x) || !std::isfinite(L.y) || !std::isfinite(L.z)) L = Rgb(0.0);
                        sum += L;
                        const double l = luminance(L);
                        lum += l, lum2 += l * l;
                    }
                    const Rgb m = sum / double(s.spp);
                    img.rgb[3 * index] = float(m.x), img.rgb[3 * index + 1] = float(m.y),
                                img.rgb[3 * index + 2] = float(m.z);
                    const double ml = lum / s.spp;
                    img.variance[index] =
                        s.spp > 1 ? float(std::max(0.0, (lum2 - s.spp * ml * ml) / (s.spp - 1)) / s.spp) : 0.f;
                }
            const int finished = ++done;
            if (s.progress) s.progress(double(finished) / (tx * ty));
        }
    });
    if (stats) {
        stats->rays = rays.combine([](uint64_t a, uint64_t b) { return a + b; });
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return img;
}

}  // namespace knit
