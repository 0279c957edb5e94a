// binding_evaluate_simd.hpp (internal) — the binding's per-vertex gather (binding_gather.hpp)
// four vertices at a time in AVX2, chosen at run time (binding_evaluate_simd.cpp).
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace knit::impl {

// What the gather reads: per yarn vertex its triangle, barycentrics (b1, b2) and height; per
// triangle its corners; per mesh vertex its position and normal.
struct GatherArrays {
    const uint32_t* face;
    const glm::dvec2* bary;
    const double* height;
    const glm::uvec3* tri;
    const glm::dvec3* X;
    const glm::dvec3* N;
};

// True when this CPU runs the AVX2 kernels (util::avx2Kernels: checked once; the build itself
// assumes only x86-64's SSE2, so the same binary runs everywhere; KNIT_SIMD=0 turns them off).
bool evaluateSimdAvailable();

// Vertices [begin, end) four at a time: P[i] = sum b x + h n, N[i] = n = the normalized
// interpolated normal ((0, 0, 1) when it vanishes). The same double operations in the same
// order as BindingGather (no fused multiply-add), so the results are its results bit for bit.
// Returns the first vertex not done (fewer than four remain); call only when
// evaluateSimdAvailable().
size_t evaluateDoubleSimd(const GatherArrays& a, size_t begin, size_t end, glm::dvec3* P, glm::dvec3* N);

}  // namespace knit::impl
