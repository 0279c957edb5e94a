// frames_transport.cpp — the normal-independent part of the double-reflection transport for a
// block of steps (frames_transport.hpp), per step or four steps at a time in AVX2.
//
// Per step from (x0, t0) to (x1, t1), as transport() in frames.cpp computes it:
//   v1 = x1 - x0; zero segment when v1.v1 <= (64 eps)^2 max(x0.x0, x1.x1); a1 = 2 / v1.v1;
//   tL = t0 - (a1 (v1.t0)) v1 (t0 without a first reflection); v2 = t1 - tL; b2 = 2 / v2.v2,
//   no second reflection when v2.v2 <= 1e-24; a reversal when t0.t1 < 0; then the matrix of
//   both reflections. Dot products are (x x' + y y') + z z' as glm::dot. The AVX2 versions load
//   four points (twelve doubles) into x, y, z registers and do the same operations lane by lane
//   (no FMA), so they are the scalar code's results bit for bit.
#include "frames_transport.hpp"

#include <algorithm>
#include <cfloat>

#include <glm/geometric.hpp>

#include "util/simd.hpp"  // KNIT_AVX2

#if KNIT_HAVE_AVX2_KERNELS
#include "simd_lanes.hpp"
#endif

namespace knit::impl {
namespace {

using glm::dvec3;

constexpr double kZeroScale = 64.0 * DBL_EPSILON;  // frames.cpp's zeroSegment
constexpr double kZeroScale2 = kZeroScale * kZeroScale;

void stepScalar(const dvec3* x, const dvec3* t, size_t i, size_t k, TransportBlock& b) {
    const dvec3 &x0 = x[i], &x1 = x[i + 1], &t0 = t[i], &t1 = t[i + 1];
    const dvec3 v1 = x1 - x0;
    const double vv = glm::dot(v1, v1);
    const bool zero = vv <= kZeroScale2 * std::max(glm::dot(x0, x0), glm::dot(x1, x1));
    const double a1 = zero ? 0.0 : 2.0 / vv;
    const dvec3 tL = zero ? t0 : t0 - (a1 * glm::dot(v1, t0)) * v1;
    const dvec3 v2 = t1 - tL;
    const double c2 = glm::dot(v2, v2);
    const double b2 = c2 > 1e-24 ? 2.0 / c2 : 0.0;
    // M = I - p v1^T - w v2^T with u = a1 v1, w = b2 v2, p = u - (v2.u) w.
    const dvec3 u = a1 * v1, w = b2 * v2;
    const dvec3 p = u - glm::dot(v2, u) * w;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) b.m[3 * r + c][k] = ((r == c ? 1.0 : 0.0) - p[r] * v1[c]) - w[r] * v2[c];
    b.reversal[k] = glm::dot(t0, t1) < 0.0;
}

#if KNIT_HAVE_AVX2_KERNELS

using lanes::divide;
using lanes::dot;
using lanes::Lanes;
using lanes::load4;
using lanes::store4;
using lanes::sub;

// Steps i .. i + 3 into block slots k .. k + 3 (points i .. i + 4 are read): stepScalar's
// operations lane by lane.
KNIT_AVX2 void fourSteps(const dvec3* x, const dvec3* t, size_t i, size_t k, TransportBlock& b) {
    const Lanes x0 = load4(x + i), x1 = load4(x + i + 1), t0 = load4(t + i), t1 = load4(t + i + 1);
    const Lanes v1 = sub(x1, x0);
    const __m256d vv = dot(v1, v1);
    const __m256d limit = _mm256_mul_pd(_mm256_set1_pd(kZeroScale2), _mm256_max_pd(dot(x0, x0), dot(x1, x1)));
    const __m256d zero = _mm256_cmp_pd(vv, limit, _CMP_LE_OQ);
    const __m256d a1 = _mm256_andnot_pd(zero, _mm256_div_pd(_mm256_set1_pd(2.0), vv));
    const __m256d s1 = _mm256_mul_pd(a1, dot(v1, t0));
    const Lanes tL = {_mm256_blendv_pd(_mm256_sub_pd(t0.x, _mm256_mul_pd(s1, v1.x)), t0.x, zero),
                      _mm256_blendv_pd(_mm256_sub_pd(t0.y, _mm256_mul_pd(s1, v1.y)), t0.y, zero),
                      _mm256_blendv_pd(_mm256_sub_pd(t0.z, _mm256_mul_pd(s1, v1.z)), t0.z, zero)};
    const Lanes v2 = sub(t1, tL);
    const __m256d c2 = dot(v2, v2);
    const __m256d bent = _mm256_cmp_pd(c2, _mm256_set1_pd(1e-24), _CMP_GT_OQ);
    const __m256d b2 = _mm256_and_pd(bent, _mm256_div_pd(_mm256_set1_pd(2.0), c2));
    const Lanes u = {_mm256_mul_pd(a1, v1.x), _mm256_mul_pd(a1, v1.y), _mm256_mul_pd(a1, v1.z)};
    const Lanes w = {_mm256_mul_pd(b2, v2.x), _mm256_mul_pd(b2, v2.y), _mm256_mul_pd(b2, v2.z)};
    const __m256d cu = dot(v2, u);
    const __m256d p[3] = {_mm256_sub_pd(u.x, _mm256_mul_pd(cu, w.x)), _mm256_sub_pd(u.y, _mm256_mul_pd(cu, w.y)),
                          _mm256_sub_pd(u.z, _mm256_mul_pd(cu, w.z))};
    const __m256d wr[3] = {w.x, w.y, w.z}, a[3] = {v1.x, v1.y, v1.z}, c[3] = {v2.x, v2.y, v2.z};
    const __m256d one = _mm256_set1_pd(1.0), none = _mm256_setzero_pd();
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) {
            const __m256d e = _mm256_sub_pd(r == col ? one : none, _mm256_mul_pd(p[r], a[col]));
            _mm256_storeu_pd(b.m[3 * r + col] + k, _mm256_sub_pd(e, _mm256_mul_pd(wr[r], c[col])));
        }
    const int reversal = _mm256_movemask_pd(_mm256_cmp_pd(dot(t0, t1), _mm256_setzero_pd(), _CMP_LT_OQ));
    for (int j = 0; j < 4; ++j) b.reversal[k + j] = ((reversal >> j) & 1) != 0;
}

// Eight float32 lanes per coordinate.
struct FLanes {
    __m256 x, y, z;
};
KNIT_AVX2 inline FLanes load8(float* const* c, size_t i) {
    return {_mm256_loadu_ps(c[0] + i), _mm256_loadu_ps(c[1] + i), _mm256_loadu_ps(c[2] + i)};
}
KNIT_AVX2 inline __m256 fdot(const FLanes& a, const FLanes& b) {
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)), _mm256_mul_ps(a.z, b.z));
}
// Four double lanes rounded to float32 and stored at c[0..2] + k.
KNIT_AVX2 inline void storeFloat(float* const* c, size_t k, const Lanes& l) {
    _mm_storeu_ps(c[0] + k, _mm256_cvtpd_ps(l.x));
    _mm_storeu_ps(c[1] + k, _mm256_cvtpd_ps(l.y));
    _mm_storeu_ps(c[2] + k, _mm256_cvtpd_ps(l.z));
}

// Steps i .. i + 7 into slots k .. k + 7 in float32 from the curve's float copies (no
// zero-length segment): stepScalar's operations eight lanes at a time, widened to double.
KNIT_AVX2 void eightStepsFloat(const FloatCurve& f, size_t i, size_t k, TransportBlock& b) {
    const FLanes v1 = load8(f.v, i), t0 = load8(f.t, i), t1 = load8(f.t, i + 1);
    const __m256 a1 = _mm256_div_ps(_mm256_set1_ps(2.0f), fdot(v1, v1));
    const __m256 s1 = _mm256_mul_ps(a1, fdot(v1, t0));
    const FLanes v2 = {_mm256_sub_ps(t1.x, _mm256_sub_ps(t0.x, _mm256_mul_ps(s1, v1.x))),
                       _mm256_sub_ps(t1.y, _mm256_sub_ps(t0.y, _mm256_mul_ps(s1, v1.y))),
                       _mm256_sub_ps(t1.z, _mm256_sub_ps(t0.z, _mm256_mul_ps(s1, v1.z)))};
    const __m256 c2 = fdot(v2, v2);
    const __m256 bent = _mm256_cmp_ps(c2, _mm256_set1_ps(1e-24f), _CMP_GT_OQ);
    const __m256 b2 = _mm256_and_ps(bent, _mm256_div_ps(_mm256_set1_ps(2.0f), c2));
    const FLanes u = {_mm256_mul_ps(a1, v1.x), _mm256_mul_ps(a1, v1.y), _mm256_mul_ps(a1, v1.z)};
    const FLanes w = {_mm256_mul_ps(b2, v2.x), _mm256_mul_ps(b2, v2.y), _mm256_mul_ps(b2, v2.z)};
    const __m256 cu = fdot(v2, u);
    const __m256 p[3] = {_mm256_sub_ps(u.x, _mm256_mul_ps(cu, w.x)), _mm256_sub_ps(u.y, _mm256_mul_ps(cu, w.y)),
                         _mm256_sub_ps(u.z, _mm256_mul_ps(cu, w.z))};
    const __m256 wr[3] = {w.x, w.y, w.z}, a[3] = {v1.x, v1.y, v1.z}, c[3] = {v2.x, v2.y, v2.z};
    const __m256 one = _mm256_set1_ps(1.0f), none = _mm256_setzero_ps();
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) {
            const __m256 e = _mm256_sub_ps(_mm256_sub_ps(r == col ? one : none, _mm256_mul_ps(p[r], a[col])),
                                           _mm256_mul_ps(wr[r], c[col]));
            _mm256_storeu_pd(b.m[3 * r + col] + k, _mm256_cvtps_pd(_mm256_castps256_ps128(e)));
            _mm256_storeu_pd(b.m[3 * r + col] + k + 4, _mm256_cvtps_pd(_mm256_extractf128_ps(e, 1)));
        }
    const int reversal = _mm256_movemask_ps(_mm256_cmp_ps(fdot(t0, t1), _mm256_setzero_ps(), _CMP_LT_OQ));
    for (int j = 0; j < 8; ++j) b.reversal[k + j] = ((reversal >> j) & 1) != 0;
}

KNIT_AVX2 size_t unitDirectionsAvx2(const dvec3* x, size_t n, dvec3* T, dvec3* N, const FloatCurve* f) {
    size_t k = 0;
    for (; k + 5 <= n; k += 4) {  // segments k .. k + 3 read points k .. k + 4
        const Lanes p = load4(x + k), q = load4(x + k + 1);
        const Lanes v = sub(q, p);
        const __m256d vv = dot(v, v);
        const __m256d limit = _mm256_mul_pd(_mm256_set1_pd(kZeroScale2), _mm256_max_pd(dot(p, p), dot(q, q)));
        if (_mm256_movemask_pd(_mm256_cmp_pd(vv, limit, _CMP_LE_OQ)) != 0) break;  // a zero-length segment
        const Lanes d = divide(v, _mm256_sqrt_pd(vv));
        if (f) storeFloat(f->v, k, v);
        store4(T + k, d);
        store4(N + k, d);
    }
    return k;
}

KNIT_AVX2 size_t pointTangentsAvx2(const dvec3* N, dvec3* T, size_t begin, size_t end, const FloatCurve* f) {
    size_t i = begin;
    for (; i + 4 <= end; i += 4) {
        const Lanes prev = load4(N + i - 1), next = load4(T + i);
        const Lanes sum = {_mm256_add_pd(prev.x, next.x), _mm256_add_pd(prev.y, next.y), _mm256_add_pd(prev.z, next.z)};
        const __m256d len = _mm256_sqrt_pd(dot(sum, sum));
        const __m256d ok = _mm256_cmp_pd(len, _mm256_set1_pd(1e-6), _CMP_GT_OQ);
        const Lanes unit = divide(sum, len);
        const Lanes t = {_mm256_blendv_pd(next.x, unit.x, ok), _mm256_blendv_pd(next.y, unit.y, ok),
                         _mm256_blendv_pd(next.z, unit.z, ok)};
        if (f) storeFloat(f->t, i, t);
        store4(T + i, t);
    }
    return i;
}

#endif

}  // namespace

size_t unitDirections(const dvec3* x, size_t n, dvec3* T, dvec3* N, bool simd, const FloatCurve* f) {
#if KNIT_HAVE_AVX2_KERNELS
    if (simd) return unitDirectionsAvx2(x, n, T, N, f);
#endif
    (void)x, (void)n, (void)T, (void)N, (void)simd, (void)f;
    return 0;
}

size_t pointTangents(const dvec3* N, dvec3* T, size_t begin, size_t end, bool simd, const FloatCurve* f) {
#if KNIT_HAVE_AVX2_KERNELS
    if (simd) return pointTangentsAvx2(N, T, begin, end, f);
#endif
    (void)N, (void)T, (void)end, (void)simd, (void)f;
    return begin;
}

void transportCoefficients(const dvec3* x, const dvec3* t, size_t first, size_t count, TransportBlock& b, bool simd,
                           size_t begin, const FloatCurve* f) {
    size_t k = begin;
#if KNIT_HAVE_AVX2_KERNELS
    if (simd && f)
        for (; k + 8 <= count; k += 8) eightStepsFloat(*f, first + k, k, b);
    if (simd)
        for (; k + 4 <= count; k += 4) fourSteps(x, t, first + k, k, b);
#endif
    (void)f;
    for (; k < count; ++k) stepScalar(x, t, first + k, k, b);
}

}  // namespace knit::impl
