// knit/view.hpp — a camera looking at the scene (perspective or orthographic) and what it sees:
// the projection of world points to pixels, the frustum planes and the world size of one pixel.
// The view drives culling and level of detail per UV cell (knit/detail.hpp).
#pragma once
#include <array>

#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"

namespace knit {

struct View {
    glm::dvec3 eye{0.0, 0.0, 1.0};  // world space (metres)
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};   // need not be perpendicular to the view direction
    double fovDegrees = 30;         // vertical field of view (perspective)
    int width = 512, height = 384;  // image size in pixels
    bool orthographic = false;
    double orthoHeight = 1.0;  // world height of the image (orthographic)
};

// Throws knit::Error naming the setting at fault (knit/setting_spelling.hpp): the eye position, target
// position, up direction or field of view when not finite; "the eye position and the target
// position must differ"; the up direction parallel to the view direction; the field of view
// outside (0, 180); the image width or height below 1; an orthographic height that is not
// positive.
void validateView(const View& view);

// The camera's orthonormal frame: forward (eye to target), right, and up (image up).
struct ViewBasis {
    glm::dvec3 forward{0.0, 0.0, -1.0}, right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0};
};
ViewBasis viewBasis(const View& view);

// A world point in the image: x, y in pixels (origin top-left, y down) and its depth along the
// view direction (metres; <= 0 behind the eye, where x and y mean nothing).
glm::dvec3 projectToPixel(const View& view, const glm::dvec3& world);

// A plane n . p + d = 0 with n pointing into the frustum.
struct Plane {
    glm::dvec3 n{0.0};
    double d = 0;
    double distance(const glm::dvec3& p) const;  // > 0 inside
};
// The four side planes of the image and the eye plane (depth > 0), pointing inward.
std::array<Plane, 5> frustumPlanes(const View& view);

// The world size of one pixel at `depth` metres in front of the eye (constant when orthographic).
double pixelFootprint(const View& view, double depth);

// The default camera (the one `knit render` uses without --eye): looks at the sphere around the
// mesh's bounding box grown by `margin` (the yarns' height above the surface plus their radius) along the
// mesh's area-weighted mean normal (the cloth's front); for a closed mesh (mean normal below 1e-3
// of the summed normal lengths) along the shortest axis of the bounds. Image up is +y unless the
// cloth faces +-y, then -z. The sphere fills the vertical field of view of `settings`, whose
// field of view and image size are kept.
View frameMesh(const BaseMesh& mesh, double margin, const View& settings);

// The centre and radius of the sphere around the mesh's bounds grown by `margin`, and the camera
// frame of the default view (what frameMesh frames).
struct FramedBounds {
    glm::dvec3 centre{0.0};
    double radius = 0;
    glm::dvec3 normal{0.0, 0.0, 1.0};  // the direction the camera looks back along
    glm::dvec3 up{0.0, 1.0, 0.0};
    glm::dvec3 right{1.0, 0.0, 0.0};
};
FramedBounds framedBounds(const BaseMesh& mesh, double margin);

}  // namespace knit
