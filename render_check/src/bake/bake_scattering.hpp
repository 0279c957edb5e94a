// bake_scattering.hpp — internal: the light paths of a bake through the flat plies of a pattern
// cell (bake.hpp), and the scattering table measured with them (knit/surface_scattering.hpp).
#pragma once
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

#include "knit/bake.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/ply_material.hpp"
#include "knit/surface_scattering.hpp"
#include "tracing/trace_scene.hpp"

namespace knit {

// Small counter-based random numbers: one stream per sample, independent of threads.
struct BakeRandom {
    uint64_t state;
    double uniform();
};

// Where a path through the plies leaves them.
struct Escape {
    bool escaped = false;  // false: absorbed, or still inside after the last bounce
    glm::vec3 direction{0.f};
    Rgb weight{0.0};  // the path's throughput (BSDF weights)
};

// The flat cloth repeats with the pattern's period: a ray that would leave the generated tiles
// sideways is moved back by whole periods and goes on, until it hits yarn or leaves the layer
// of yarns through its top or bottom plane. So oblique rays see an endless cloth.
struct PeriodicCloth {
    glm::dvec2 period{1.0};        // px, py (metres)
    glm::dvec2 centre{0.0};        // the baked cell's centre (metres)
    double zTop = 0, zBottom = 0;  // planes above and below every yarn (metres)
    double reach = 0.5;            // horizontal distance (periods) a ray may go from the centre
};

class PlyPaths {
public:
    PlyPaths(const TraceScene& scene, const PlyMaterial& material, const FiberTables& tables,
             const PeriodicCloth& cloth);
    // The first hit of the ray from org along d in the endless cloth (see PeriodicCloth); p is
    // the hit point, near the baked cell. `from`: the hit the ray leaves.
    bool intersect(glm::vec3 org, const glm::vec3& d, TraceHit& hit, glm::vec3& p,
                   const TraceHit* from = nullptr) const;
    // A BSDF-sampled path from hit h at point p, reached along direction d: at most maxBounces
    // bounces.
    Escape follow(TraceHit h, glm::vec3 p, glm::vec3 d, BakeRandom& rng, int maxBounces) const;
    const TraceScene& scene() const { return scene_; }

private:
    const TraceScene& scene_;
    const PlyMaterial& material_;
    const FiberTables& tables_;
    glm::vec2 period_, centre_;    // scene units
    float zTop_, zBottom_, step_;  // scene units; step_: horizontal distance per traced piece
};

struct ScatteringSetup {
    glm::dvec2 cellMin{0.0}, cellSize{1.0};  // the cell (pattern metres), as the texture bake's
    double zTop = 0, zBottom = 0;            // planes above and below every yarn (metres)
    int side = 8;                            // SurfaceScattering::side
    int pathsPerBin = 4096;
    std::vector<int> pathsOfBin;  // per bin, overriding pathsPerBin (focusedPaths); empty: none
    int maxBounces = 8;
    uint64_t seed = 1;
};

// Paths per bin for `pathsPerBin` on average: (1 - share) of them evenly, `share` by the focus
// directions' weights on their interpolation corners (every bin gets at least one path).
std::vector<int> focusedPaths(const SurfaceScattering& layout, int pathsPerBin,
                              const std::vector<ScatteringFocus>& focus, double share);

// Per out bin, pathsPerBin (or pathsOfBin) rays along -out with uniform random directions in the bin, entering
// through the plane on out's side at uniform random points of the cell; rays that cross without
// a hit add to pass, the others are followed and their escape directions binned with their
// weights. Deterministic for any thread count.
SurfaceScattering measureScattering(const PlyPaths& paths, const ScatteringSetup& setup);

}  // namespace knit
