// binding_gather_simd.hpp (internal) — the AVX2 group kernel behind binding_evaluate_simd.cpp,
// shared with the strain deformer's kernel (deform/strain_displace_simd.cpp), which adds its
// displacement to each gathered point while it is still in a register. Include only from files
// built for x86-64 with GCC or Clang (KNIT_HAVE_AVX2_KERNELS); every function carries KNIT_AVX2.
//
// Per group of four yarn vertices: (1) per vertex, its three corners and corner normals are
// loaded as (x, y, z, 0) and interpolated in one register (three multiplies, two adds, as the
// scalar code's per-component b0 x0 + b1 x1 + b2 x2); (2) the four squared normal lengths
// (x x + y y) + z z by a 4x4 transpose, one square root and one division for all four;
// (3) per vertex, the normal scaled (or (0, 0, 1)), the position p + h n, then the caller's
// hook on (p, n); (4) stored with overlapping unaligned stores (each store's fourth lane is
// overwritten by the next vertex's; the group's last vertex is stored exactly, so no store
// reaches beyond the group).
// Only multiplies, adds, a square root and a division, each correctly rounded and in the
// scalar order, and no FMA (the target is "avx2", not "fma"): bit for bit the scalar result.
#pragma once
#include <immintrin.h>

#include <algorithm>
#include <cstddef>

#include "binding_evaluate_simd.hpp"
#include "util/simd.hpp"

namespace knit::impl::gather_simd {

// One vertex's interpolated position and normal (x, y, z, 0).
struct Corner {
    __m256d p, n;
};

// Yarn vertex i's barycentrics broadcast: b0 = (1 - b1) - b2, as the scalar code.
struct Bary {
    __m256d b0, b1, b2;
};

KNIT_AVX2 inline Bary barycentrics(const glm::dvec2* bary, size_t i) {
    Bary b;
    b.b1 = _mm256_broadcast_sd(&bary[i].x);
    b.b2 = _mm256_broadcast_sd(&bary[i].y);
    b.b0 = _mm256_sub_pd(_mm256_sub_pd(_mm256_set1_pd(1.0), b.b1), b.b2);
    return b;
}

// b0 x0 + b1 x1 + b2 x2 in the scalar order.
KNIT_AVX2 inline __m256d blend3(const Bary& b, __m256d x0, __m256d x1, __m256d x2) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(b.b0, x0), _mm256_mul_pd(b.b1, x1)), _mm256_mul_pd(b.b2, x2));
}

KNIT_AVX2 inline Corner interpolate(const GatherArrays& a, size_t i, __m256i mask3) {
    const glm::uvec3 f = a.tri[a.face[i]];
    const Bary b = barycentrics(a.bary, i);
    Corner c;
    c.p = blend3(b, _mm256_maskload_pd(&a.X[f.x].x, mask3), _mm256_maskload_pd(&a.X[f.y].x, mask3),
                 _mm256_maskload_pd(&a.X[f.z].x, mask3));
    c.n = blend3(b, _mm256_maskload_pd(&a.N[f.x].x, mask3), _mm256_maskload_pd(&a.N[f.y].x, mask3),
                 _mm256_maskload_pd(&a.N[f.z].x, mask3));
    return c;
}

// The four vertices' (x x + y y) + z z, one per lane.
KNIT_AVX2 inline __m256d squaredLengths(const Corner* c) {
    const __m256d m0 = _mm256_mul_pd(c[0].n, c[0].n), m1 = _mm256_mul_pd(c[1].n, c[1].n);
    const __m256d m2 = _mm256_mul_pd(c[2].n, c[2].n), m3 = _mm256_mul_pd(c[3].n, c[3].n);
    const __m256d t0 = _mm256_unpacklo_pd(m0, m1), t1 = _mm256_unpackhi_pd(m0, m1);  // (x0 x1 z0 z1), (y0 y1 . .)
    const __m256d t2 = _mm256_unpacklo_pd(m2, m3), t3 = _mm256_unpackhi_pd(m2, m3);
    const __m256d xx = _mm256_permute2f128_pd(t0, t2, 0x20), yy = _mm256_permute2f128_pd(t1, t3, 0x20);
    const __m256d zz = _mm256_permute2f128_pd(t0, t2, 0x31);
    return _mm256_add_pd(_mm256_add_pd(xx, yy), zz);
}

template <int J>
KNIT_AVX2 inline __m256d lane(__m256d v) {
    return _mm256_permute4x64_pd(v, J * 0x55);
}

// Vertex J of the group: its unit normal and its position p + h n.
template <int J>
KNIT_AVX2 inline void finish(const GatherArrays& a, size_t i, const Corner& c, __m256d inv, __m256d ok, __m256d& p,
                             __m256d& n) {
    const __m256d up = _mm256_setr_pd(0.0, 0.0, 1.0, 0.0);
    n = _mm256_blendv_pd(up, _mm256_mul_pd(c.n, lane<J>(inv)), lane<J>(ok));
    p = _mm256_add_pd(c.p, _mm256_mul_pd(_mm256_broadcast_sd(&a.height[i + J]), n));
}

// The exact three doubles of the group's last vertex.
KNIT_AVX2 inline void store3(double* out, __m256d v) {
    _mm_storeu_pd(out, _mm256_castpd256_pd128(v));
    _mm_store_sd(out + 2, _mm256_extractf128_pd(v, 1));
}

// Vertices per chunk: the chunk's interpolations and inverse normal lengths are computed first
// (independent square roots and divisions, which the core overlaps), then its stores; one group
// at a time stalled on each group's square root and division.
constexpr size_t kChunk = 32;

// 1 / sqrt(x), correctly rounded twice as the scalar code's 1.0 / std::sqrt(x).
KNIT_AVX2 inline __m256d exactInverseRoot(__m256d x) { return _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_sqrt_pd(x)); }

// The chunk's interpolations and inverse lengths (and whether each length is positive).
KNIT_AVX2 inline void interpolateChunk(const GatherArrays& a, size_t i, size_t groups, __m256i mask3, Corner* c,
                                       __m256d* inv, __m256d* ok) {
    for (size_t g = 0; g < groups; ++g) {
        Corner* cg = c + 4 * g;
        const size_t v = i + 4 * g;
        cg[0] = interpolate(a, v, mask3);
        cg[1] = interpolate(a, v + 1, mask3);
        cg[2] = interpolate(a, v + 2, mask3);
        cg[3] = interpolate(a, v + 3, mask3);
        const __m256d len2 = squaredLengths(cg);
        inv[g] = exactInverseRoot(len2);
        ok[g] = _mm256_cmp_pd(len2, _mm256_setzero_pd(), _CMP_GT_OQ);
    }
}

// One group's four vertices finished, passed through `hook(i, n, p)` (which may change p) and stored.
template <class Hook>
KNIT_AVX2 inline void finishGroup(const GatherArrays& a, size_t i, const Corner* cg, __m256d inv, __m256d ok,
                                  glm::dvec3* P, glm::dvec3* N, const Hook& hook) {
    __m256d p[4], n[4];
    finish<0>(a, i, cg[0], inv, ok, p[0], n[0]);
    finish<1>(a, i, cg[1], inv, ok, p[1], n[1]);
    finish<2>(a, i, cg[2], inv, ok, p[2], n[2]);
    finish<3>(a, i, cg[3], inv, ok, p[3], n[3]);
    for (int j = 0; j < 4; ++j) hook(i + size_t(j), n[j], p[j]);
    double* outP = &P[i].x;
    double* outN = &N[i].x;
    for (int j = 0; j < 3; ++j) {
        _mm256_storeu_pd(outP + 3 * j, p[j]);
        _mm256_storeu_pd(outN + 3 * j, n[j]);
    }
    store3(outP + 9, p[3]);
    store3(outN + 9, n[3]);
}

// Vertices [begin, end) in groups of four; returns the first vertex not done.
template <class Hook>
KNIT_AVX2 inline size_t evaluateGroups(const GatherArrays& a, size_t begin, size_t end, glm::dvec3* P, glm::dvec3* N,
                                       const Hook& hook) {
    const __m256i mask3 = _mm256_setr_epi64x(-1, -1, -1, 0);
    Corner c[kChunk];
    __m256d inv[kChunk / 4], ok[kChunk / 4];
    size_t i = begin;
    while (i + 4 <= end) {
        const size_t groups = std::min(kChunk, end - i) / 4;
        interpolateChunk(a, i, groups, mask3, c, inv, ok);
        for (size_t g = 0; g < groups; ++g, i += 4) finishGroup(a, i, c + 4 * g, inv[g], ok[g], P, N, hook);
    }
    return i;
}

}  // namespace knit::impl::gather_simd
