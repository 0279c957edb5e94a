// resample_curve.hpp (internal) — the per-curve pieces of resampleYarns (resample.cpp), for
// callers that resample curve by curve (PlyGenerator: makePlies, streaming export) without
// materializing every resampled curve.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/resample.hpp"

namespace knit {

// Reusable buffers of resampleCurve (one per thread).
struct ResampleScratch {
    std::vector<glm::dvec3> points, normals, samples;
    std::vector<double> knots, inverseKnots, inversePairs;  // inverses: resampleCurveWithLayout's
};

// The checks resampleYarns makes before it resamples: positive finite spacing, consistent
// offsets, one normal per point (or none), finite points and normals. Throws knit::Error naming
// the curve and point.
void validateResampleInput(const MappedYarns& yarns, const ResampleOptions& options);

// What resampleCurve decided for one curve, to replay on another pose of it (animation: the
// point count and order stay those of the rest pose).
struct ResampleLayout {
    std::vector<uint32_t> kept;    // input points kept after merging repeats (index within the curve)
    std::vector<uint32_t> pieces;  // per segment between kept points (closed: the closing one too), >= 1
};

// Resamples curve `c` of `yarns` (exactly as resampleYarns does) and appends its points to
// `points` and, when `normals` is not null and the yarns have normals, its normals to
// `normals`. Returns the number of points appended. The input must have passed
// validateResampleInput; never throws (except std::bad_alloc). `layout` (optional) receives
// the decisions made (replaced).
size_t resampleCurve(const MappedYarns& yarns, size_t c, double spacing, std::vector<glm::dvec3>& points,
                     std::vector<glm::dvec3>* normals, ResampleScratch& scratch, ResampleLayout* layout = nullptr);

// The per-point colours `in` (curve `c`'s first point at in[0]) of a curve resampled with
// `layout`, appended to `out`: a kept point keeps its colour, an inserted point takes the colour
// of the nearer end of its piece (colours change between stitches, never blend). Returns the
// number appended (what resampleCurve appended to its points).
size_t resampleColours(const glm::vec3* in, bool closed, const ResampleLayout& layout, std::vector<glm::vec3>& out);
// The per-point twist `in` (curve's first point at in[0], radians; MappedYarns::twist) of a curve
// resampled with a layout (its kept points and pieces, as resampleCurveWithLayout), written to
// `out`: linear in the piece parameter j / k between kept points (twist changes smoothly with the
// strain). Returns the number written (what resampling writes).
size_t resampleTwist(const float* in, bool closed, const uint32_t* kept, size_t keptCount, const uint32_t* pieces,
                     double* out);
// Resamples curve `c` of `curves` (a deformed pose of the curve a layout was recorded on) with
// that layout's kept points and piece counts, writing sum(pieces) + (open ? 1 : 0) points (or the
// 0 / 1 kept points of a degenerate curve) to `out`. On the recording pose it gives
// resampleCurve's points. Never throws, never allocates once the scratch has grown.
size_t resampleCurveWithLayout(const Polylines& curves, size_t c, const uint32_t* kept, size_t keptCount,
                               const uint32_t* pieces, glm::dvec3* out, ResampleScratch& scratch);

// A lower bound of the points resampleCurve produces for curve `c` (the sum of
// ceil(chord / spacing) over its segments, plus the last point of an open curve): for planning
// batches and reserving memory.
size_t estimateResampledSize(const Polylines& curves, size_t c, double spacing);

}  // namespace knit
