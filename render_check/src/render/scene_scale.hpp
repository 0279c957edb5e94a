// scene_scale.hpp (internal) — renders at any scale: a scene far from metre size (1e-8 m, 1e-30 m,
// 1e12 m) is traced as a copy scaled to unit size about its centre, so float32 geometry, ray
// epsilons and Embree's bounds stay in range. Scenes of ordinary size are traced as they are.
#pragma once
#include <optional>

#include "knit/scene.hpp"

namespace knit::impl {

// The plies' bounding-sphere radius range traced without scaling (metres).
constexpr double kMinTracedRadius = 1e-3;
constexpr double kMaxTracedRadius = 1e4;

// The scene scaled to a ply bounding radius of 1 about the plies' bounds centre (mesh, yarns,
// plies and their radii; directions and UV data unchanged), or nothing when its size is within
// [kMinTracedRadius, kMaxTracedRadius] or it has no plies. Throws knit::Error when the ply points
// are not finite.
std::optional<Scene> sceneAtTracingScale(const Scene& scene);

}  // namespace knit::impl
