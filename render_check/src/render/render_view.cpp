// The view and light of `knit render` (see render_view.hpp and knit/render.hpp).
#include "render_view.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace impl {

double sceneMargin(const Scene& scene) {
    if (scene.detail()) return scene.detail()->margin;
    return scene.yarnMargin();
}

RectLight defaultLight(const Scene& scene, LightPlacement light, double irradiance) {
    const FramedBounds f = framedBounds(scene.mesh(), sceneMargin(scene));
    const bool front = light == LightPlacement::Front;
    const double lightSize = front ? f.radius : 3.0 * f.radius, lightDist = 2.5 * f.radius;
    const glm::dvec3 dir = front ? glm::normalize(f.normal + 0.4 * f.right + 0.4 * f.up) : -f.normal;
    const glm::dvec3 lc = f.centre + lightDist * dir;
    // Light facing the centre: edges perpendicular to dir, cross(edgeU, edgeV) = -dir.
    const glm::dvec3 lh = std::abs(dir.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 eu = glm::normalize(glm::cross(dir, lh)) * lightSize;
    const glm::dvec3 ev = glm::normalize(glm::cross(eu, dir)) * lightSize;
    RectLight l;
    l.corner = lc - 0.5 * eu - 0.5 * ev;
    l.edgeU = eu;
    l.edgeV = ev;
    // Irradiance at the centre ~ L A / d^2 (light facing it): choose L for the requested irradiance.
    l.radiance = Rgb(irradiance * lightDist * lightDist / (lightSize * lightSize));
    return l;
}

Camera cameraOf(const View& view) {
    Camera c;
    c.eye = view.eye, c.target = view.target, c.up = view.up, c.fovYDegrees = view.fovDegrees;
    return c;
}

}  // namespace impl

View renderView(const Scene& scene, const RenderOptions& o) {
    View v = scene.detail() ? scene.detail()->view : o.view.value_or(View{});
    v.fovDegrees = o.fovDegrees, v.width = o.width, v.height = o.height;
    if (!scene.detail() && !o.view) v = frameMesh(scene.mesh(), impl::sceneMargin(scene), v);
    if (v.orthographic) throw Error("render: orthographic views are not rendered (the tracer's camera is a pinhole)");
    validateView(v);
    return v;
}

}  // namespace knit
