// binding_evaluate_simd.cpp — BindingGather four vertices at a time in AVX2 (x86-64 only,
// chosen at run time: the functions carry their own target attribute, the rest of the build
// stays SSE2). The group kernel is binding_gather_simd.hpp's (shared with the strain deformer);
// here it runs with nothing added after the gather.
#include "binding_evaluate_simd.hpp"

#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include "binding_gather_simd.hpp"
#endif

namespace knit::impl {

#if KNIT_HAVE_AVX2_KERNELS
namespace {

// The geometric evaluation changes nothing after the gather.
struct NoHook {
    KNIT_AVX2 void operator()(size_t, __m256d, __m256d&) const {}
};

}  // namespace

bool evaluateSimdAvailable() { return util::avx2Kernels(); }

size_t evaluateDoubleSimd(const GatherArrays& a, size_t begin, size_t end, glm::dvec3* P, glm::dvec3* N) {
    return gather_simd::evaluateGroups(a, begin, end, P, N, NoHook{});
}

#else  // not x86-64 with GCC or Clang: the scalar loop only

bool evaluateSimdAvailable() { return false; }
size_t evaluateDoubleSimd(const GatherArrays&, size_t begin, size_t, glm::dvec3*, glm::dvec3*) { return begin; }

#endif

}  // namespace knit::impl
