// helices_simd.cpp — helicesCosSin (helices_simd.hpp): per group of four centre points, the
// points, tangents and normals as x, y, z registers, B = T x N as glm::cross, then per ply
// c = ct cos_i - st sin_i, s = st cos_i + ct sin_i, radial = c N + s B, P = X + R radial, stored
// back as four points. No FMA (target "avx2"): the scalar loop's results bit for bit.
#include "helices_simd.hpp"

#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include "simd_lanes.hpp"
#endif

namespace knit::impl {
namespace {

#if KNIT_HAVE_AVX2_KERNELS

using lanes::Lanes;
using lanes::load4;
using lanes::store4;

KNIT_AVX2 size_t helicesAvx2(const HelixInput& in, glm::dvec3* P, glm::dvec3* D) {
    const __m256d R = _mm256_set1_pd(in.R);
    size_t j = 0;
    for (; j + 4 <= in.m; j += 4) {
        const Lanes x = load4(in.X + j), t = load4(in.T + j), n = load4(in.N + j);
        // glm::cross(t, n) = (t.y n.z - n.y t.z, t.z n.x - n.z t.x, t.x n.y - n.x t.y)
        const Lanes b = {_mm256_sub_pd(_mm256_mul_pd(t.y, n.z), _mm256_mul_pd(n.y, t.z)),
                         _mm256_sub_pd(_mm256_mul_pd(t.z, n.x), _mm256_mul_pd(n.z, t.x)),
                         _mm256_sub_pd(_mm256_mul_pd(t.x, n.y), _mm256_mul_pd(n.x, t.y))};
        // (cos, sin) of four points: c0 s0 c1 s1 | c2 s2 c3 s3 -> c0 c1 c2 c3, s0 s1 s2 s3.
        const __m256d p01 = _mm256_loadu_pd(&in.phase[j].x), p23 = _mm256_loadu_pd(&in.phase[j + 2].x);
        const __m256d ct = _mm256_permute4x64_pd(_mm256_unpacklo_pd(p01, p23), 0xD8);
        const __m256d st = _mm256_permute4x64_pd(_mm256_unpackhi_pd(p01, p23), 0xD8);
        for (uint32_t i = 0; i < in.plies; ++i) {
            const __m256d cp = _mm256_set1_pd(in.cosPly[i]), sp = _mm256_set1_pd(in.sinPly[i]);
            const __m256d c = _mm256_sub_pd(_mm256_mul_pd(ct, cp), _mm256_mul_pd(st, sp));
            const __m256d s = _mm256_add_pd(_mm256_mul_pd(st, cp), _mm256_mul_pd(ct, sp));
            const Lanes radial = {_mm256_add_pd(_mm256_mul_pd(c, n.x), _mm256_mul_pd(s, b.x)),
                                  _mm256_add_pd(_mm256_mul_pd(c, n.y), _mm256_mul_pd(s, b.y)),
                                  _mm256_add_pd(_mm256_mul_pd(c, n.z), _mm256_mul_pd(s, b.z))};
            store4(P + i * in.m + j,
                   {_mm256_add_pd(x.x, _mm256_mul_pd(R, radial.x)), _mm256_add_pd(x.y, _mm256_mul_pd(R, radial.y)),
                    _mm256_add_pd(x.z, _mm256_mul_pd(R, radial.z))});
            if (D) store4(D + i * in.m + j, radial);
        }
    }
    return j;
}

#endif

}  // namespace

size_t helicesCosSin(const HelixInput& in, glm::dvec3* P, glm::dvec3* D, bool simd) {
#if KNIT_HAVE_AVX2_KERNELS
    if (simd) return helicesAvx2(in, P, D);
#endif
    (void)in, (void)P, (void)D, (void)simd;
    return 0;
}

}  // namespace knit::impl
