// scene_scale.hpp (internal) — renders at any scale: a scene far from metre size (1e-8 m, 1e-30 m,
// 1e12 m) is traced as a copy scaled to unit size about its centre, so float32 geometry, ray
// epsilons and Embree's bounds stay in range. Scenes of ordinary size are traced as they are.
//
// The copy is made with Scene::fromParts, which holds no pattern or placement (its yarn margin
// then comes from the binding): what reads those (the bake of a view's surface level, the surface
// texture's repeats, the yarns' margin that frames the default camera and light) reads the
// original scene; the view, the light and the margin are mapped into the copy with TracingScale,
// and the camera and light a render reports are mapped back. The copy keeps the scene's ply
// options (scaled), which the yarn level's radius and shading read.
#pragma once
#include <optional>

#include "knit/path_tracer.hpp"
#include "knit/scene.hpp"
#include "knit/view.hpp"

namespace knit::impl {

// The plies' bounding-sphere radius range traced without scaling (metres).
constexpr double kMinTracedRadius = 1e-3;
constexpr double kMaxTracedRadius = 1e4;

// The map from a scene's space (metres) to the space it is traced in: p -> (p - centre) * scale.
// The default is the identity (exactly: p - 0 and p * 1 round to p).
struct TracingScale {
    glm::dvec3 centre{0.0};
    double scale = 1;

    glm::dvec3 point(const glm::dvec3& p) const { return (p - centre) * scale; }
    // Eye, target and orthographic height mapped; directions, field of view and size kept.
    View view(View v) const;
    // Corner and edges mapped; radiance kept (uniform scaling leaves radiance unchanged).
    RectLight light(RectLight l) const;

    // The way back to metres (the identity returns its argument unchanged).
    bool identity() const { return scale == 1 && centre == glm::dvec3(0.0); }
    glm::dvec3 worldPoint(const glm::dvec3& p) const { return identity() ? p : p / scale + centre; }
    View worldView(View v) const;
    RectLight worldLight(RectLight l) const;
};

// A scene far from metre size at unit size, and the map into it.
struct TracingCopy {
    Scene scene;  // mesh, yarns, binding heights, plies, a view's pieces and the ply options scaled
    TracingScale scale;
};

// The map to a ply bounding radius of 1 about the plies' bounds centre, or nothing when the
// scene's size is within [kMinTracedRadius, kMaxTracedRadius] or it has no plies (a view without
// plies: its base mesh). Throws knit::Error when the ply points are not finite.
std::optional<TracingScale> tracingScale(const Scene& scene);

// The scene scaled by tracingScale (directions and UV data unchanged), or nothing when it is traced
// as it is.
std::optional<TracingCopy> sceneAtTracingScale(const Scene& scene);

}  // namespace knit::impl
