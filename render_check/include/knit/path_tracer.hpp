// knit/path_tracer.hpp — what the path tracer takes and makes: pinhole camera, rectangular area
// light, image. The tracer itself (unidirectional path tracing with next-event estimation and MIS
// on the internal Embree scene) is render_check/src/tracing/render_image.hpp; renderScene (render.hpp) is
// its public entry.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/ply_material.hpp"

namespace knit {

struct Camera {
    glm::dvec3 eye{0, 0, 1}, target{0.0}, up{0, 1, 0};  // world space (metres)
    double fovYDegrees = 30;
};

// One-sided emitter: the parallelogram corner + a edgeU + b edgeV, emitting towards cross(edgeU, edgeV).
// It has no body: seen from behind it is not there (rays pass), so a front light placed between
// the camera and the cloth never hides part of the view (it did with narrow fields of view).
struct RectLight {
    glm::dvec3 corner{0.0}, edgeU{1, 0, 0}, edgeV{0, 1, 0};
    Rgb radiance{0.0};
};

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;       // linear, row-major from the top, 3 floats per pixel
    std::vector<float> variance;  // per pixel: variance of the mean luminance estimate
    Rgb pixel(int x, int y) const;
    Rgb mean() const;
};

}  // namespace knit
