// frames_transport.cpp — the normal-independent part of the double-reflection transport for a
// block of steps (frames_transport.hpp), per step or four steps at a time in AVX2.
//
// Per step from (x0, t0) to (x1, t1), as transport() in frames.cpp computes it:
//   v1 = x1 - x0; zero segment when v1.v1 <= (64 eps)^2 max(x0.x0, x1.x1); a1 = 2 / v1.v1;
//   tL = t0 - (a1 (v1.t0)) v1 (t0 without a first reflection); v2 = t1 - tL; b2 = 2 / v2.v2,
//   no second reflection when v2.v2 <= 1e-24; a reversal when t0.t1 < 0.
// Dot products are (x x' + y y') + z z' as glm::dot. The AVX2 version loads four points (twelve
// doubles) into x, y, z registers and does the same operations lane by lane (no FMA).
#include "frames_transport.hpp"

#include <algorithm>
#include <cfloat>

#include <glm/geometric.hpp>

#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include <immintrin.h>
#endif

namespace knit::impl {
namespace {

using glm::dvec3;

constexpr double kZeroScale = 64.0 * DBL_EPSILON;  // frames.cpp's zeroSegment
constexpr double kZeroScale2 = kZeroScale * kZeroScale;

void stepScalar(const dvec3* x, const dvec3* t, size_t i, size_t k, TransportBlock& b) {
    const dvec3 &x0 = x[i], &x1 = x[i + 1], &t0 = t[i], &t1 = t[i + 1];
    uint8_t flags = glm::dot(t0, t1) < 0.0 ? TransportBlock::kReversal : 0;
    const dvec3 v1 = x1 - x0;
    const double vv = glm::dot(v1, v1);
    dvec3 tL = t0;
    double a1 = 0.0;
    if (vv <= kZeroScale2 * std::max(glm::dot(x0, x0), glm::dot(x1, x1))) {
        flags |= TransportBlock::kZeroSegment;
    } else {
        a1 = 2.0 / vv;
        tL = t0 - (a1 * glm::dot(v1, t0)) * v1;
    }
    const dvec3 v2 = t1 - tL;
    const double c2 = glm::dot(v2, v2);
    if (!(c2 > 1e-24)) flags |= TransportBlock::kStraight;
    for (int c = 0; c < 3; ++c) {
        b.v1[c][k] = v1[c];
        b.v2[c][k] = v2[c];
    }
    b.a1[k] = a1;
    b.b2[k] = c2 > 1e-24 ? 2.0 / c2 : 0.0;
    b.flags[k] = flags;
}

#if KNIT_HAVE_AVX2_KERNELS

struct Lanes {
    __m256d x, y, z;
};

// Points p[0..3] (twelve doubles x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3) as x, y, z lanes.
KNIT_AVX2 inline Lanes load4(const dvec3* p) {
    const double* d = &p->x;
    const __m256d a = _mm256_loadu_pd(d), bb = _mm256_loadu_pd(d + 4), c = _mm256_loadu_pd(d + 8);
    const __m256d mid = _mm256_permute2f128_pd(a, c, 0x21);  // a2 a3 c0 c1
    Lanes l;
    l.x = _mm256_blend_pd(_mm256_blend_pd(a, mid, 0b1010), bb, 0b0100);                        // a0 a3 b2 c1
    l.y = _mm256_permute_pd(_mm256_blend_pd(_mm256_blend_pd(a, bb, 0b1001), c, 0b0100), 0b0101);  // a1 b0 b3 c2
    l.z = _mm256_blend_pd(_mm256_blend_pd(mid, bb, 0b0010), c, 0b1000);                       // a2 b1 c0 c3
    return l;
}

KNIT_AVX2 inline __m256d dot(const Lanes& a, const Lanes& b) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)), _mm256_mul_pd(a.z, b.z));
}

KNIT_AVX2 inline Lanes sub(const Lanes& a, const Lanes& b) {
    return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}

// Steps i .. i + 3 into block slots k .. k + 3 (points i .. i + 4 are read).
KNIT_AVX2 void fourSteps(const dvec3* x, const dvec3* t, size_t i, size_t k, TransportBlock& b) {
    const Lanes x0 = load4(x + i), x1 = load4(x + i + 1), t0 = load4(t + i), t1 = load4(t + i + 1);
    const __m256d zero = _mm256_setzero_pd();
    const __m256d reversal = _mm256_cmp_pd(dot(t0, t1), zero, _CMP_LT_OQ);
    const Lanes v1 = sub(x1, x0);
    const __m256d vv = dot(v1, v1);
    const __m256d limit = _mm256_mul_pd(_mm256_set1_pd(kZeroScale2), _mm256_max_pd(dot(x0, x0), dot(x1, x1)));
    const __m256d zeroSegment = _mm256_cmp_pd(vv, limit, _CMP_LE_OQ);
    const __m256d a1 = _mm256_div_pd(_mm256_set1_pd(2.0), vv);
    const __m256d s1 = _mm256_mul_pd(a1, dot(v1, t0));
    const Lanes reflected = {_mm256_sub_pd(t0.x, _mm256_mul_pd(s1, v1.x)), _mm256_sub_pd(t0.y, _mm256_mul_pd(s1, v1.y)),
                             _mm256_sub_pd(t0.z, _mm256_mul_pd(s1, v1.z))};
    const Lanes tL = {_mm256_blendv_pd(reflected.x, t0.x, zeroSegment), _mm256_blendv_pd(reflected.y, t0.y, zeroSegment),
                      _mm256_blendv_pd(reflected.z, t0.z, zeroSegment)};
    const Lanes v2 = sub(t1, tL);
    const __m256d c2 = dot(v2, v2);
    const __m256d bent = _mm256_cmp_pd(c2, _mm256_set1_pd(1e-24), _CMP_GT_OQ);
    _mm256_storeu_pd(b.v1[0] + k, v1.x);
    _mm256_storeu_pd(b.v1[1] + k, v1.y);
    _mm256_storeu_pd(b.v1[2] + k, v1.z);
    _mm256_storeu_pd(b.v2[0] + k, v2.x);
    _mm256_storeu_pd(b.v2[1] + k, v2.y);
    _mm256_storeu_pd(b.v2[2] + k, v2.z);
    _mm256_storeu_pd(b.a1 + k, _mm256_andnot_pd(zeroSegment, a1));
    _mm256_storeu_pd(b.b2 + k, _mm256_and_pd(bent, _mm256_div_pd(_mm256_set1_pd(2.0), c2)));
    const int z = _mm256_movemask_pd(zeroSegment), s = ~_mm256_movemask_pd(bent), r = _mm256_movemask_pd(reversal);
    for (int j = 0; j < 4; ++j)
        b.flags[k + j] = static_cast<uint8_t>(((z >> j) & 1) * TransportBlock::kZeroSegment |
                                              ((s >> j) & 1) * TransportBlock::kStraight |
                                              ((r >> j) & 1) * TransportBlock::kReversal);
}

#endif

}  // namespace

void transportCoefficients(const dvec3* x, const dvec3* t, size_t first, size_t count, TransportBlock& b) {
    size_t k = 0;
#if KNIT_HAVE_AVX2_KERNELS
    if (util::avx2Kernels())
        for (; k + 4 <= count; k += 4) fourSteps(x, t, first + k, k, b);
#endif
    for (; k < count; ++k) stepScalar(x, t, first + k, k, b);
}

}  // namespace knit::impl
