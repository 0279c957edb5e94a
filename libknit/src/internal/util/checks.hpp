// util/checks.hpp — finiteness and consistency checks used at stage boundaries (internal).
#pragma once
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace knit::util {

inline bool finite(double v) { return std::isfinite(v); }
inline bool finite(const glm::dvec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }
inline bool finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
inline bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Finite and of unit length within `tolerance` (on the squared length).
inline bool finiteUnit(const glm::dvec3& v, double tolerance = 1e-6) {
    const double l = glm::dot(v, v);
    return std::isfinite(l) && std::abs(l - 1.0) < tolerance;
}

// A positive, finite number (NaN fails).
inline bool positiveFinite(double v) { return v > 0 && std::isfinite(v); }
// Both components positive and finite (a size or a repeat count in UV).
inline bool positiveFinite(const glm::dvec2& v) { return positiveFinite(v.x) && positiveFinite(v.y); }

}  // namespace knit::util
