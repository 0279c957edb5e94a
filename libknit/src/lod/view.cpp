// The view: validation naming the CLI options, projection, frustum planes, pixel footprint and
// the default camera framing a base mesh.
#include "knit/view.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

double tanHalfFov(const View& v) { return std::tan(v.fovDegrees * util::kPi / 360.0); }

// Half the image's world width and height at depth 1 (perspective) or in all (orthographic).
glm::dvec2 halfExtent(const View& v) {
    const double h = v.orthographic ? 0.5 * v.orthoHeight : tanHalfFov(v);
    return {h * double(v.width) / double(v.height), h};
}

}  // namespace

void validateView(const View& v) {
    if (!util::finite(v.eye)) throw Error("the eye position must be three finite numbers");
    if (!util::finite(v.target)) throw Error("the target position must be three finite numbers");
    if (!util::finite(v.up)) throw Error("the up direction must be three finite numbers");
    if (!std::isfinite(v.fovDegrees)) throw Error("the field of view must be a finite number of degrees");
    const glm::dvec3 dir = v.target - v.eye;
    const double len = glm::length(dir);
    if (!(len > 0) || !std::isfinite(len)) throw Error("the eye position and the target position must differ");
    const double upLen = glm::length(v.up);
    if (!(upLen > 0)) throw Error("the up direction must not be the zero vector");
    if (glm::length(glm::cross(dir / len, v.up / upLen)) < 1e-6)
        throw Error("the up direction must not be parallel to the view direction, from the eye position to the target "
                    "position");
    if (!v.orthographic && !(v.fovDegrees > 0 && v.fovDegrees < 180))
        throw Error("the field of view must be between 0 and 180 degrees (got " + std::to_string(v.fovDegrees) + ")");
    if (v.width < 1) throw Error("the image width must be at least 1 pixel (got " + std::to_string(v.width) + ")");
    if (v.height < 1) throw Error("the image height must be at least 1 pixel (got " + std::to_string(v.height) + ")");
    if (v.orthographic && !util::positiveFinite(v.orthoHeight))
        throw Error("the orthographic image height must be positive and finite");
}

ViewBasis viewBasis(const View& v) {
    ViewBasis b;
    b.forward = glm::normalize(v.target - v.eye);
    b.right = glm::normalize(glm::cross(b.forward, v.up));
    b.up = glm::cross(b.right, b.forward);
    return b;
}

glm::dvec3 projectToPixel(const View& v, const glm::dvec3& world) {
    const ViewBasis b = viewBasis(v);
    const glm::dvec3 d = world - v.eye;
    const double depth = glm::dot(d, b.forward);
    const glm::dvec2 half = halfExtent(v);
    const double scale = v.orthographic ? 1.0 : depth;
    const double sx = glm::dot(d, b.right) / (scale * half.x), sy = glm::dot(d, b.up) / (scale * half.y);
    return {0.5 * (sx + 1.0) * v.width, 0.5 * (1.0 - sy) * v.height, depth};
}

double Plane::distance(const glm::dvec3& p) const { return glm::dot(n, p) + d; }

std::array<Plane, 5> frustumPlanes(const View& v) {
    const ViewBasis b = viewBasis(v);
    const glm::dvec2 half = halfExtent(v);
    std::array<Plane, 5> planes;
    auto through = [&](const glm::dvec3& n, const glm::dvec3& point) { return Plane{n, -glm::dot(n, point)}; };
    if (v.orthographic) {
        // Step: slabs at +-half around the view axis.
        planes[0] = through(b.right, v.eye - half.x * b.right);
        planes[1] = through(-b.right, v.eye + half.x * b.right);
        planes[2] = through(b.up, v.eye - half.y * b.up);
        planes[3] = through(-b.up, v.eye + half.y * b.up);
    } else {
        // Step: planes through the eye and the image edges (inward normals).
        planes[0] = through(glm::normalize(half.x * b.forward + b.right), v.eye);
        planes[1] = through(glm::normalize(half.x * b.forward - b.right), v.eye);
        planes[2] = through(glm::normalize(half.y * b.forward + b.up), v.eye);
        planes[3] = through(glm::normalize(half.y * b.forward - b.up), v.eye);
    }
    planes[4] = through(b.forward, v.eye);
    return planes;
}

double pixelFootprint(const View& v, double depth) {
    const double worldHeight = v.orthographic ? v.orthoHeight : 2.0 * std::max(depth, 0.0) * tanHalfFov(v);
    return worldHeight / double(v.height);
}

FramedBounds framedBounds(const BaseMesh& mesh, double margin) {
    FramedBounds f;
    // Step 1: the sphere around the positions' bounds, grown by the margin (every point within
    // `margin` of the mesh lies inside it).
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (mesh.positions.empty()) lo = hi = glm::dvec3(0.0);
    f.centre = 0.5 * (lo + hi);
    // A degenerate mesh (one point, no margin) gets a micrometre; any other keeps its own size,
    // however small (a fixed micrometre floor framed a 1e-12 m scene a million times too wide).
    const double radius = 0.5 * glm::length(hi - lo) + margin;
    f.radius = radius > 0 ? radius : 1e-6;
    // Step 2: the cloth's front, the area-weighted mean normal; a closed mesh has none (its normals
    // cancel up to rounding): the shortest axis of the bounds instead.
    glm::dvec3 normal(0.0);
    double normalLengths = 0;
    const std::vector<glm::dvec3>& x = mesh.positions;
    for (const glm::uvec3& t : mesh.faces)
        if (t.x < x.size() && t.y < x.size() && t.z < x.size()) {
            const glm::dvec3 n = glm::cross(x[t.y] - x[t.x], x[t.z] - x[t.x]);
            normal += n, normalLengths += glm::length(n);
        }
    if (glm::length(normal) > 1e-3 * normalLengths && normalLengths > 0) {
        f.normal = glm::normalize(normal);
    } else {
        const glm::dvec3 ext = hi - lo + 2.0 * margin;
        const int axis = ext.x <= ext.y && ext.x <= ext.z ? 0 : (ext.y <= ext.z ? 1 : 2);
        f.normal = glm::dvec3(0.0);
        f.normal[axis] = 1.0;
    }
    // Step 3: image up +y (glTF's up) unless the cloth faces +-y (lies flat); then -z, glTF's
    // forward, so a flat cloth is framed as the same cloth standing in the xy plane would be.
    const glm::dvec3 helper = std::abs(f.normal.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
    f.right = glm::normalize(glm::cross(helper, f.normal));
    f.up = glm::cross(f.normal, f.right);
    return f;
}

View frameMesh(const BaseMesh& mesh, double margin, const View& settings) {
    const FramedBounds f = framedBounds(mesh, margin);
    View v = settings;
    const double dist = f.radius / std::sin(settings.fovDegrees * util::kPi / 360.0);
    v.eye = f.centre + dist * f.normal;
    v.target = f.centre;
    v.up = f.up;
    v.orthoHeight = 2.0 * f.radius;
    return v;
}

}  // namespace knit
