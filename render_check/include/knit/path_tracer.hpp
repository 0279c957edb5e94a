// knit/path_tracer.hpp — pinhole camera, rectangular area light + constant environment, unidirectional
// path tracing with next-event estimation and MIS (power heuristic), on a TraceScene.
//
// Deterministic for a seed and any thread count: every pixel has its own random stream seeded from
// (seed, pixel index); tiles are rendered in parallel with TBB. Plies use the ply BSDF in the frame
// of plyShadingFrame(); the base mesh (when present) is a two-sided Lambertian reflector. Paths
// whose direction is on a different side of the geometric normal than of the shading normal carry
// no energy (no light leaks through the fiber perturbation).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/fiber_tables.hpp"
#include "knit/ply_material.hpp"

namespace knit {

class TraceScene;  // render_check internal (src/trace_scene.hpp): the Embree scene to trace

struct Camera {
    glm::dvec3 eye{0, 0, 1}, target{0.0}, up{0, 1, 0};  // world space (metres)
    double fovYDegrees = 30;
};

// One-sided emitter: the parallelogram corner + a edgeU + b edgeV, emitting towards cross(edgeU, edgeV).
// It has no body: seen from behind it is not there (rays pass), so a front light placed between
// the camera and the cloth never hides part of the view (it did with narrow fields of view).
struct RectLight {
    glm::dvec3 corner{0.0}, edgeU{1, 0, 0}, edgeV{0, 1, 0};
    Rgb radiance{0.0};
};

struct TraceSettings {
    int width = 64, height = 64, spp = 16;
    uint64_t seed = 1;
    int maxDepth = 16;           // bounces; Russian roulette from depth 3
    Camera camera;
    RectLight light;
    Rgb environment{0.0};        // constant radiance from every direction
    Rgb baseAlbedo{0.5};
    std::function<void(double fractionDone)> progress;  // called from worker threads (may be empty)
};

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;       // linear, row-major from the top, 3 floats per pixel
    std::vector<float> variance;  // per pixel: variance of the mean luminance estimate
    Rgb pixel(int x, int y) const;
    Rgb mean() const;
};

struct TraceStats {
    uint64_t rays = 0;  // intersect + occlusion queries
    double seconds = 0;
};

Image renderImage(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables,
                  const TraceSettings& settings, TraceStats* stats = nullptr);

}  // namespace knit
