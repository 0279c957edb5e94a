// render_view.hpp (internal) — the light of `knit render`, derived like its default camera from
// the base mesh grown by the yarns' margin (never from generated geometry), so a scene lights the
// same at every level of detail.
#pragma once
#include "knit/path_tracer.hpp"
#include "knit/render.hpp"
#include "render/scene_scale.hpp"

namespace knit::impl {

// The yarns' margin of a scene: the scene's own when built for a view, else Scene::yarnMargin
// (from the pattern; from the binding for a scene made from parts).
double sceneMargin(const Scene& scene);

// Front: a light of the framed radius up and to the right of the default camera. Back: a
// lightbox three times larger behind the cloth, so transmission shows everywhere. Its radiance
// gives `irradiance` at the framed centre.
RectLight defaultLight(const Scene& scene, LightPlacement light, double irradiance);
// The same for a mesh grown by `margin`.
RectLight defaultLight(const BaseMesh& mesh, double margin, LightPlacement light, double irradiance);

// How renderScene frames a scene it traces as `tracedMesh` (the scene's mesh, or its copy's at
// unit size with `scale` the map into it), all in traced units: the view (renderView's), the
// default light and the centre of the framed bounds (the geometry's origin). The yarns' margin is
// the scene's own, mapped. knit::Error naming the setting for a bad view.
struct TracedFrame {
    View view;
    RectLight light;
    glm::dvec3 centre{0.0};
};
TracedFrame tracedFrame(const Scene& scene, const BaseMesh& tracedMesh, const TracingScale& scale,
                        const RenderOptions& options);

Camera cameraOf(const View& view);

}  // namespace knit::impl
