// util/simd.hpp — whether this CPU runs the library's AVX2 kernels (internal).
//
// The build assumes only x86-64's SSE2, so one binary runs on every x86-64 CPU; the hot loops
// that have an AVX2 version (binding evaluation, ply frames) mark those functions with
// KNIT_AVX2 and call them only when avx2Kernels() is true. Each AVX2 kernel does the scalar
// loop's double operations in the same order with no fused multiply-add (the target is "avx2",
// which does not enable FMA), so its results are the scalar loop's bit for bit.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KNIT_HAVE_AVX2_KERNELS 1
#define KNIT_AVX2 __attribute__((target("avx2")))
#else
#define KNIT_HAVE_AVX2_KERNELS 0
#endif

namespace knit::util {

// True when the CPU has AVX2 and KNIT_SIMD is not "0" in the environment (read once; the
// variable exists to compare against the scalar loops).
bool avx2Kernels();

}  // namespace knit::util
