// render_view.hpp (internal) — the light of `knit render`, derived like its default camera from
// the base mesh grown by the yarns' margin (never from generated geometry), so a scene lights the
// same at every level of detail.
#pragma once
#include "knit/path_tracer.hpp"
#include "knit/render.hpp"

namespace knit::impl {

// The yarns' margin of a scene: the scene's own when built for a view, else Scene::yarnMargin
// (from the pattern; from the binding for a scene made from parts).
double sceneMargin(const Scene& scene);

// Front: a light of the framed radius up and to the right of the default camera. Back: a
// lightbox three times larger behind the cloth, so transmission shows everywhere. Its radiance
// gives `irradiance` at the framed centre.
RectLight defaultLight(const Scene& scene, LightPlacement light, double irradiance);

Camera cameraOf(const View& view);

}  // namespace knit::impl
