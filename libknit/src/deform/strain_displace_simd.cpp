// strain_displace_simd.cpp — the strain deformer's per-yarn-vertex displacement (at the mesh's
// UV vertices) added inside the binding's AVX2 gather (binding/binding_gather_simd.hpp), while
// each gathered point and normal is still in a register: per vertex, the three corner rows are
// one 256-bit load each, interpolated b0 d0 + b1 d1 + b2 d2 and (x, y, z) + w n added, in the
// scalar order (strain_displace.hpp) and without FMA, so bit for bit the scalar result. A
// vertex whose triangle did not move keeps its gathered point (a blend, not a branch).
#include "strain_displace.hpp"

#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include "binding/binding_gather_simd.hpp"
#endif

namespace knit::impl {

#if KNIT_HAVE_AVX2_KERNELS
namespace {

struct Displace {
    const GatherArrays& a;
    const StrainRows& s;

    KNIT_AVX2 void operator()(size_t i, __m256d n, __m256d& p) const {
        const StrainCorners& c = s.corners[a.face[i]];
        const uint32_t v = s.cellVertex[i];
        const gather_simd::Bary b = gather_simd::barycentrics(a.bary, i);
        const __m256d e =
            gather_simd::blend3(b, _mm256_loadu_pd(&s.d[c.row[0] + v].x), _mm256_loadu_pd(&s.d[c.row[1] + v].x),
                                _mm256_loadu_pd(&s.d[c.row[2] + v].x));
        const __m256d out = _mm256_add_pd(e, _mm256_mul_pd(gather_simd::lane<3>(e), n));  // (x, y, z) + w n
        const __m256d moved = _mm256_castsi256_pd(_mm256_set1_epi64x(-int64_t(c.flag & kStrainMoved)));
        p = _mm256_blendv_pd(p, _mm256_add_pd(p, out), moved);
    }
};

}  // namespace

size_t evaluateDisplacedSimd(const GatherArrays& a, const StrainRows& s, size_t begin, size_t end, glm::dvec3* P,
                             glm::dvec3* N) {
    return gather_simd::evaluateGroups(a, begin, end, P, N, Displace{a, s});
}

#else  // not x86-64 with GCC or Clang: the scalar loop only

size_t evaluateDisplacedSimd(const GatherArrays&, const StrainRows&, size_t begin, size_t, glm::dvec3*, glm::dvec3*) {
    return begin;
}

#endif

}  // namespace knit::impl
