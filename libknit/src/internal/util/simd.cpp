// util/simd.cpp — the run-time CPU check behind the AVX2 kernels (util/simd.hpp).
#include "util/simd.hpp"

#include <cstdlib>
#include <cstring>

namespace knit::util {
namespace {

bool detectAvx2() {
    const char* env = std::getenv("KNIT_SIMD");
    if (env && std::strcmp(env, "0") == 0) return false;
#if KNIT_HAVE_AVX2_KERNELS
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
#else
    return false;
#endif
}

}  // namespace

bool avx2Kernels() {
    static const bool available = detectAvx2();
    return available;
}

}  // namespace knit::util
