// helices_simd.hpp (internal) — the ply helices of PlyKernel::sweepWithCosSin (plies.cpp) four
// centre points at a time in AVX2 (helices_simd.cpp).
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace knit::impl {

// What the helices read: the framed centreline (m points), the phase per point as (cos, sin),
// the ply count and phase offsets, the centre radius.
struct HelixInput {
    const glm::dvec3* X;
    const glm::dvec3* T;
    const glm::dvec3* N;
    const glm::dvec2* phase;
    size_t m;
    uint32_t plies;
    const double* cosPly;
    const double* sinPly;
    double R;
};

// Points j = 0, 4, ... while j + 4 <= m: ply i's point j at P[i m + j] = X + R (c N + s (T x N))
// with c, s the cosine and sine of the phase plus ply i's offset (and the radial direction at
// D[i m + j] unless D is null), the same operations as the scalar loop lane by lane. Returns the
// first point not done (0 without `simd`).
size_t helicesCosSin(const HelixInput& in, glm::dvec3* P, glm::dvec3* D, bool simd);

}  // namespace knit::impl
