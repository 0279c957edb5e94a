// simd_lanes.hpp (internal) — four points of a dvec3 array as x, y, z AVX2 registers, for the
// plies' AVX2 kernels (frames_transport.cpp, helices_simd.cpp, resample.cpp). Include only where
// KNIT_HAVE_AVX2_KERNELS (util/simd.hpp); call only from KNIT_AVX2 functions.
#pragma once
#include <immintrin.h>

#include <glm/vec3.hpp>

#include "util/simd.hpp"

namespace knit::impl::lanes {

using glm::dvec3;

struct Lanes {
    __m256d x, y, z;
};

// Points p[0..3] (twelve doubles x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3) as x, y, z lanes.
KNIT_AVX2 inline Lanes load4(const dvec3* p) {
    const double* d = &p->x;
    const __m256d a = _mm256_loadu_pd(d), bb = _mm256_loadu_pd(d + 4), c = _mm256_loadu_pd(d + 8);
    const __m256d mid = _mm256_permute2f128_pd(a, c, 0x21);  // a2 a3 c0 c1
    Lanes l;
    l.x = _mm256_blend_pd(_mm256_blend_pd(a, mid, 0b1010), bb, 0b0100);                           // a0 a3 b2 c1
    l.y = _mm256_permute_pd(_mm256_blend_pd(_mm256_blend_pd(a, bb, 0b1001), c, 0b0100), 0b0101);  // a1 b0 b3 c2
    l.z = _mm256_blend_pd(_mm256_blend_pd(mid, bb, 0b0010), c, 0b1000);                           // a2 b1 c0 c3
    return l;
}

// The inverse of load4: x, y, z lanes stored as four points.
KNIT_AVX2 inline void store4(dvec3* p, const Lanes& l) {
    double* d = &p->x;
    const __m256d t0 = _mm256_unpacklo_pd(l.x, l.y);        // x0 y0 | x2 y2
    const __m256d u = _mm256_shuffle_pd(l.z, l.x, 0b1010);  // z0 x1 | z2 x3
    const __m256d v = _mm256_shuffle_pd(l.y, l.z, 0b1111);  // y1 z1 | y3 z3
    _mm256_storeu_pd(d, _mm256_permute2f128_pd(t0, u, 0x20));
    _mm256_storeu_pd(d + 4, _mm256_permute2f128_pd(v, t0, 0x30));
    _mm256_storeu_pd(d + 8, _mm256_permute2f128_pd(u, v, 0x31));
}

KNIT_AVX2 inline Lanes divide(const Lanes& a, __m256d s) {
    return {_mm256_div_pd(a.x, s), _mm256_div_pd(a.y, s), _mm256_div_pd(a.z, s)};
}

KNIT_AVX2 inline __m256d dot(const Lanes& a, const Lanes& b) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)), _mm256_mul_pd(a.z, b.z));
}

KNIT_AVX2 inline Lanes sub(const Lanes& a, const Lanes& b) {
    return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}

KNIT_AVX2 inline Lanes add(const Lanes& a, const Lanes& b) {
    return {_mm256_add_pd(a.x, b.x), _mm256_add_pd(a.y, b.y), _mm256_add_pd(a.z, b.z)};
}

KNIT_AVX2 inline Lanes scale(const Lanes& a, __m256d s) {
    return {_mm256_mul_pd(a.x, s), _mm256_mul_pd(a.y, s), _mm256_mul_pd(a.z, s)};
}

}  // namespace knit::impl::lanes
