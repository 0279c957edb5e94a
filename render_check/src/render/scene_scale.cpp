// A scene scaled to unit size for tracing (see scene_scale.hpp).
#include "scene_scale.hpp"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"

namespace knit::impl {
namespace {

void scalePoints(std::vector<glm::dvec3>& points, const glm::dvec3& centre, double scale) {
    for (glm::dvec3& p : points) p = (p - centre) * scale;
}

// A view's levels and pieces scaled like the scene (directions, levels and cells unchanged).
SceneDetail scaledDetail(SceneDetail d, const glm::dvec3& centre, double s) {
    d.view.eye = (d.view.eye - centre) * s;
    d.view.target = (d.view.target - centre) * s;
    d.view.orthoHeight *= s;
    d.margin *= s;
    scalePoints(d.pieces.plies.curves.points, centre, s);
    scalePoints(d.pieces.yarns.curves.points, centre, s);
    return d;
}

// The ply options' lengths scaled (count, twist and sampling kept; 0 = automatic stays 0).
PlyOptions scaledPlyOptions(PlyOptions o, double s) {
    o.yarnRadius *= s;
    o.centerRadius *= s;
    o.plyRadius *= s;
    o.pitch *= s;
    return o;
}

}  // namespace

View TracingScale::view(View v) const {
    v.eye = point(v.eye);
    v.target = point(v.target);
    v.orthoHeight *= scale;
    return v;
}

RectLight TracingScale::light(RectLight l) const {
    l.corner = point(l.corner);
    l.edgeU *= scale;
    l.edgeV *= scale;
    return l;
}

View TracingScale::worldView(View v) const {
    if (identity()) return v;
    v.eye = worldPoint(v.eye);
    v.target = worldPoint(v.target);
    v.orthoHeight /= scale;
    return v;
}

RectLight TracingScale::worldLight(RectLight l) const {
    if (identity()) return l;
    l.corner = worldPoint(l.corner);
    l.edgeU /= scale;
    l.edgeV /= scale;
    return l;
}

std::optional<TracingScale> tracingScale(const Scene& scene) {
    // A view may leave no plies: its base mesh decides then.
    const bool meshOnly = scene.plies().curves.points.empty() && scene.detail();
    const std::vector<glm::dvec3>& points = meshOnly ? scene.mesh().positions : scene.plies().curves.points;
    if (points.empty()) return std::nullopt;
    // The plies' bounds: their radius decides whether to scale.
    glm::dvec3 lo(points[0]), hi(points[0]);
    for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (!util::finite(lo) || !util::finite(hi))
        throw Error("cannot render: the ply curves have points that are not finite");
    const glm::dvec3 centre = 0.5 * lo + 0.5 * hi;
    const glm::dvec3 half = 0.5 * hi - 0.5 * lo;  // halves first: no overflow near 1e308
    const double e = std::max(half.x, std::max(half.y, half.z));
    const double radius = e > 0 ? e * glm::length(half / e) : 0.0;  // scaled: no overflow of the squares
    if (radius >= kMinTracedRadius && radius <= kMaxTracedRadius) return std::nullopt;
    if (!(radius > 0)) throw Error("cannot render: the ply curves have no extent (all points coincide)");
    return TracingScale{centre, 1.0 / radius};
}

std::optional<TracingCopy> sceneAtTracingScale(const Scene& scene) {
    const std::optional<TracingScale> map = tracingScale(scene);
    if (!map) return std::nullopt;
    const glm::dvec3 centre = map->centre;
    const double s = map->scale;
    // A copy scaled about the centre to radius 1.
    SceneParts parts;
    parts.mesh = scene.mesh();
    scalePoints(parts.mesh.positions, centre, s);
    parts.normals = scene.normals();
    parts.yarnRadius = scene.yarnRadius() * s;
    parts.grid = scene.grid();
    parts.binding = scene.binding();
    for (double& h : parts.binding.height) h *= s;  // metres above the surface
    parts.yarns = scene.yarns();
    scalePoints(parts.yarns.curves.points, centre, s);
    parts.plies = scene.plies();
    scalePoints(parts.plies.curves.points, centre, s);
    parts.plies.plyRadius *= s;
    parts.plies.centerRadius *= s;
    parts.plies.pitch *= s;
    if (scene.detail()) parts.detail = scaledDetail(*scene.detail(), centre, s);
    parts.plyOptions = scaledPlyOptions(scene.plyOptions(), s);
    return TracingCopy{Scene::fromParts(std::move(parts)), *map};
}

}  // namespace knit::impl
