// util/math.hpp — constants and small vector helpers shared by every library of the project
// (internal: not installed; include as "util/math.hpp").
#pragma once
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace knit::util {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kInvPi = 1.0 / kPi;

// A unit vector perpendicular to unit `t`: the coordinate axis least aligned with t (ties go to
// x, then y), with its component along t removed.
inline glm::dvec3 anyPerpendicular(const glm::dvec3& t) {
    const glm::dvec3 a = glm::abs(t);
    glm::dvec3 axis(0.0);
    if (a.x <= a.y && a.x <= a.z) axis.x = 1.0;
    else if (a.y <= a.z) axis.y = 1.0;
    else axis.z = 1.0;
    return glm::normalize(axis - glm::dot(axis, t) * t);
}

// An sRGB-encoded component in [0, 1] to linear light (IEC 61966-2-1).
inline double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
// Linear light in [0, 1] to its sRGB encoding (the inverse of srgbToLinear).
inline double linearToSrgb(double c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

}  // namespace knit::util
