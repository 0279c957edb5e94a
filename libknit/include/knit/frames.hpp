// knit/frames.hpp — rotation-minimizing frames by double reflection (Wang et al. 2008).
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/polylines.hpp"

namespace knit {

// Per point: unit tangent and unit normal (perpendicular); binormal = cross(tangent, normal).
struct Frames {
    std::vector<glm::dvec3> tangent;
    std::vector<glm::dvec3> normal;
};

struct FrameOptions {
    // Closed curves: measure the closing angle with a signed atan2 and spread the correction
    // along arc length so the frame closes without a jump.
    bool closeLoops = true;
};

// Seeds each curve's first normal with `seedNormals[first point]` projected perpendicular to the
// tangent (the surface normal: phase stable under animation); falls back to the axis least
// aligned with the tangent. Handles repeated points and straight runs.
Frames rotationMinimizingFrames(const Polylines& curves, const std::vector<glm::dvec3>* seedNormals,
                                const FrameOptions& options = {});

// Addition (backwards compatible): the per-curve kernel of rotationMinimizingFrames, for
// callers that fuse it into their own per-curve loop without whole-set frame arrays. Writes
// `count` tangents and normals for points[0, count) (closed: last -> first is a segment);
// `seedNormal` (the surface normal at points[0]) may be null. Points must be finite (not
// checked here; rotationMinimizingFrames validates). Does not allocate, never throws.
void curveFrames(const glm::dvec3* points, size_t count, bool closed, const glm::dvec3* seedNormal,
                 glm::dvec3* tangent, glm::dvec3* normal, const FrameOptions& options = {});

}  // namespace knit
