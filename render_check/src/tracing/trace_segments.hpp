// trace_segments.hpp — internal: the ply solid every geometry mode models, segment by segment: a
// cylinder of the ply radius around each segment, mitred at joints (bisector planes) except at
// joints too sharp to mitre, round (the sphere beyond the end) at open ends and sharp joints.
#pragma once
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "knit/ply_geometry.hpp"

namespace knit {

// Joints bent by more than 2 acos(kMinMitreCos) = 157 degrees are not mitred (the mitre would reach
// r / kMinMitreCos = 5 radii out): both segments are cut perpendicular to their own axis there and
// get the sphere beyond the cut, a round joint as in Embree's round curves (a flat cut alone left
// the outside of the joint open: rays passed into the ply through the missing wedge).
constexpr float kMinMitreCos = 0.2f;

inline glm::vec3 safeNormalize(const glm::vec3& v) {
    const float l = glm::length(v);
    return l > 0 ? v / l : glm::vec3(0.f);
}

// Directions a (incoming) and b (outgoing) bent too sharply to mitre.
inline bool sharpJoint(const glm::vec3& a, const glm::vec3& b) { return glm::length(a + b) < 2.f * kMinMitreCos; }

// Outward normal of ply segment s at point p: perpendicular to the axis, except beyond a round
// end (open end or joint too sharp to mitre: from the end point). u = position along the segment,
// clamped to [0, 1].
glm::vec3 axisNormal(const PlyGeometry& pg, uint32_t s, const glm::vec3& p, float& u);

}  // namespace knit
