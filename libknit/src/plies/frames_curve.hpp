// frames_curve.hpp (internal) — the per-curve kernel of rotationMinimizingFrames (frames.cpp).
#pragma once
#include <cstddef>

#include <glm/vec3.hpp>

#include "knit/frames.hpp"

namespace knit {

// The per-curve kernel of rotationMinimizingFrames, for callers that fuse it into their own
// per-curve loop without whole-set frame arrays (PlyGenerator). Writes `count` tangents and
// normals for points[0, count) (closed: last -> first is a segment); `seedNormal` (the surface
// normal at points[0]) may be null. With `seedTangent` (a unit tangent the seed normal belongs
// to, e.g. a frame transported from the rest pose) the seed is first turned by the minimal
// rotation taking seedTangent onto the curve's first tangent (parallel transport: continuous,
// no flip when the tangent passes through the seed direction), then projected as usual. Points
// must be finite (not checked here; rotationMinimizingFrames validates). Does not allocate
// (but for FramePrecision::Float32 without `floatScratch`, 6 count floats), never throws.
void curveFrames(const glm::dvec3* points, size_t count, bool closed, const glm::dvec3* seedNormal, glm::dvec3* tangent,
                 glm::dvec3* normal, const FrameOptions& options = {}, const glm::dvec3* seedTangent = nullptr,
                 float* floatScratch = nullptr);

}  // namespace knit
