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

// Ply point j of ply i: P = X + R (c N + s B) (and D = c N + s B unless D is null) with
// c = ct cp - st sp, s = st cp + ct sp the cosine and sine of the point's phase (ct, st) plus the
// ply's offset (cp, sp), B = T x N. The scalar definition the AVX2 kernels follow lane by lane.
inline void helixPoint(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& b, double ct, double st, double cp,
                       double sp, double R, glm::dvec3& P, glm::dvec3* D) {
    const double c = ct * cp - st * sp;  // cos(theta + 2 pi i / n)
    const double s = st * cp + ct * sp;  // sin(theta + 2 pi i / n)
    const glm::dvec3 radial = c * n + s * b;
    P = x + R * radial;
    if (D) *D = radial;
}

// Points j = 0, 4, ... while j + 4 <= m: ply i's point j at P[i m + j] = X + R (c N + s (T x N))
// with c, s the cosine and sine of the phase plus ply i's offset (and the radial direction at
// D[i m + j] unless D is null), the same operations as the scalar loop lane by lane. Returns the
// first point not done (0 without `simd`).
size_t helicesCosSin(const HelixInput& in, glm::dvec3* P, glm::dvec3* D, bool simd);

// All points of all plies as helicesCosSin and helixPoint compute them (bit for bit), written
// with streaming stores (the output's lines are not read first, and do not displace the caches:
// for outputs far larger than the caches, such as a whole frame's plies). Returns false, writing
// nothing, without `simd` (AVX2) or when P and D are not aligned alike.
bool helicesStreamed(const HelixInput& in, glm::dvec3* P, glm::dvec3* D, bool simd);

}  // namespace knit::impl
