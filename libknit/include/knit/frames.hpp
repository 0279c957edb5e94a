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

// The arithmetic of the frames' transport matrices (curveFrames' step 4; the chain of the normal
// and its renormalization stay in double either way). Float32: eight steps per AVX2 register
// instead of four, the matrices rounded to float32 (ply points within ~1e-5 yarn radii of the
// double path on long yarns; docs/memory-limit.md, ninth pass). Without AVX2 both are the double path.
enum class FramePrecision { Double, Float32 };

struct FrameOptions {
    // Closed curves: measure the closing angle with a signed atan2 and spread the correction
    // along arc length so the frame closes without a jump.
    bool closeLoops = true;
    FramePrecision precision = FramePrecision::Double;  // bit for bit the scalar path's
};

// Seeds each curve's first normal with `seedNormals[first point]` projected perpendicular to the
// tangent (the surface normal: phase stable under animation); falls back to the axis least
// aligned with the tangent. Handles repeated points and straight runs.
Frames rotationMinimizingFrames(const Polylines& curves, const std::vector<glm::dvec3>* seedNormals,
                                const FrameOptions& options = {});

}  // namespace knit
