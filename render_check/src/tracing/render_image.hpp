// render_image.hpp (internal) — the path tracer (path_tracer.cpp): pinhole camera, rectangular
// area light + constant environment, unidirectional path tracing with next-event estimation to the
// light and MIS (power heuristic), on a TraceScene. The environment is reached by the scattered
// rays alone. A pixel's samples are stratified over the pixel (a jittered grid of spp strata visited
// in a random order per pixel); every other number is plain random. Image::variance is the
// variance of independent samples: with the strata it is an upper bound.
//
// Deterministic for a seed and any thread count: every pixel has its own random stream seeded from
// (seed, pixel index); tiles are rendered in parallel with TBB. Each hit scatters with one of the
// kinds of bsdf/scattering.hpp: plies the ply BSDF in the frame of plyShadingFrame(), the surface
// level its measured table, the base mesh (when present) a two-sided Lambertian reflector. Paths
// whose direction is on a different side of the geometric normal than of the shading normal carry
// no energy (no light leaks through the fiber perturbation).
#pragma once
#include <cstdint>
#include <functional>

#include "knit/fiber_tables.hpp"
#include "knit/path_tracer.hpp"
#include "knit/ply_material.hpp"

namespace knit {

class TraceScene;  // trace_scene.hpp: the Embree scene to trace

struct TraceSettings {
    int width = 64, height = 64, spp = 16;
    uint64_t seed = 1;
    int maxDepth = 16;  // bounces; Russian roulette from depth 3
    Camera camera;
    RectLight light;
    Rgb environment{0.0};  // constant radiance from every direction
    Rgb baseAlbedo{0.5};
    std::function<void(double fractionDone)> progress;  // called from worker threads (may be empty)
};

struct TraceStats {
    uint64_t rays = 0;  // intersect + occlusion queries
    double seconds = 0;
};

Image renderImage(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables,
                  const TraceSettings& settings, TraceStats* stats = nullptr);

}  // namespace knit
