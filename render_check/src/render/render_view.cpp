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
    return defaultLight(scene.mesh(), sceneMargin(scene), light, irradiance);
}

RectLight defaultLight(const BaseMesh& mesh, double margin, LightPlacement light, double irradiance) {
    const FramedBounds f = framedBounds(mesh, margin);
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

TracedFrame tracedFrame(const Scene& scene, const BaseMesh& tracedMesh, const TracingScale& scale,
                        const RenderOptions& o) {
    const double margin = sceneMargin(scene) * scale.scale;
    View v = scene.detail() ? scale.view(scene.detail()->view) : o.view ? scale.view(*o.view) : View{};
    v.fovDegrees = o.fovDegrees, v.width = o.width, v.height = o.height;
    if (!scene.detail() && !o.view) v = frameMesh(tracedMesh, margin, v);
    if (v.orthographic)
        throw Error("cannot render: orthographic views are not rendered (the tracer's camera is a pinhole)");
    validateView(v);
    TracedFrame f;
    f.view = v;
    f.light = defaultLight(tracedMesh, margin, o.light, o.lightIrradiance);
    f.centre = framedBounds(tracedMesh, margin).centre;
    return f;
}

}  // namespace impl

// Framed where the scene is traced (at unit size when far from metre size: the framing's
// absolute floors stay out of the way), then mapped back to metres.
View renderView(const Scene& scene, const RenderOptions& o) {
    const std::optional<impl::TracingScale> scale = impl::tracingScale(scene);
    if (!scale) return impl::tracedFrame(scene, scene.mesh(), impl::TracingScale{}, o).view;
    BaseMesh mesh = scene.mesh();
    for (glm::dvec3& p : mesh.positions) p = scale->point(p);
    return scale->worldView(impl::tracedFrame(scene, mesh, *scale, o).view);
}

}  // namespace knit
