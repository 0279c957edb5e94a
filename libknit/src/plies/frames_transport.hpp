// frames_transport.hpp (internal) — the parts of curveFrames' double-reflection transport
// (frames.cpp, step 4) that do not depend on the normal being carried, for a block of steps at
// once (frames_transport.cpp): both reflections of a step as one 3x3 matrix. What is left per
// step is the chain of the normal itself: a matrix-vector product, without a division. Also
// curveFrames' steps 1 and 2 (segment directions, point tangents) four at a time in AVX2.
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace knit::impl {

constexpr size_t kTransportBlock = 64;

// curveFrames' float32 copies of a curve (FramePrecision::Float32), structure of arrays: the
// segment vectors v[c][k] = (x[k + 1] - x[k])[c] rounded from the double difference (step 1) and
// the point tangents t[c][i] rounded from the double tangents (step 2), so the float transport
// loads eight steps per register without converting or transposing.
struct FloatCurve {
    float* v[3];
    float* t[3];
};

// Step k of a block carries the frame from point first + k to first + k + 1: the normal r0
// becomes M r0, M = (I - b2 v2 v2^T)(I - a1 v1 v1^T) with v1 = x1 - x0, a1 = 2 / |v1|^2 (0 on a
// zero-length segment), tL = t0 - a1 (v1.t0) v1, v2 = t1 - tL, b2 = 2 / |v2|^2 (0 when
// |v2|^2 <= 1e-24): both reflections of transport() as one matrix, so the chain from normal to
// normal is three dot products (one multiply-add deep) instead of two reflections one after the
// other (two dot products, two scalings and two subtractions deep).
struct TransportBlock {
    double m[9][kTransportBlock];    // M row-major, per step
    bool reversal[kTransportBlock];  // t0.t1 < 0: transport() decides (projects the normal)
};
// Fills slots [begin, count) of `b` (count <= kTransportBlock), slot k with the step from point
// first + k, four at a time in AVX2 when `simd` (bit for bit the same either way). With `f` (the
// curve's float32 copies, a curve without zero-length segments, `simd` only): eight steps at a
// time in float32 from f, the matrices widened to double.
void transportCoefficients(const glm::dvec3* x, const glm::dvec3* t, size_t first, size_t count, TransportBlock& b,
                           bool simd, size_t begin = 0, const FloatCurve* f = nullptr);

// curveFrames' step 1 for segments k = 0, 1, ... (from x[k] to x[k + 1]) four at a time in AVX2:
// T[k] = N[k] = v / |v|, up to the first group of four that holds a zero-length segment or
// reaches x[n - 1] (closed curves' last segment wraps); returns the first segment not done
// (0 without `simd`). The caller's scalar loop does the rest, bit for bit the same.
// With `f`, the segment vectors of the segments done are also written to f->v.
size_t unitDirections(const glm::dvec3* x, size_t n, glm::dvec3* T, glm::dvec3* N, bool simd,
                      const FloatCurve* f = nullptr);

// curveFrames' step 2 for points i = begin, begin + 4, ... while i + 3 < end, where every point
// has a real direction on both sides (N[i - 1] before, T[i] after): T[i] = the normalized sum,
// or T[i] when the sum is shorter than 1e-6. Returns the first point not done (begin without
// `simd`).
// With `f`, the tangents done are also written to f->t.
size_t pointTangents(const glm::dvec3* N, glm::dvec3* T, size_t begin, size_t end, bool simd,
                     const FloatCurve* f = nullptr);

}  // namespace knit::impl
