// binding_float.hpp (internal) — the float32 per-frame evaluation shared by evaluateBindingFloat
// and evaluatePackedFloat (binding_float.cpp), eight vertices at a time in AVX2 where the CPU
// has it (binding_float_simd.cpp, bit for bit the scalar gatherFloat below).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/binding.hpp"

namespace knit::impl {

// One mesh vertex as the float32 gather reads it: the position relative to the evaluation's
// origin (subtracted in double, then rounded) and the normal, in one aligned 32-byte record
// (x y z 0 | nx ny nz 0), so a triangle corner is one load.
struct alignas(32) FloatCorner {
    float p[4];
    float n[4];
};

// The per-vertex inputs in either layout: the binding's own arrays (face, bary, height; the
// barycentrics and height rounded to float32 as they are read) or packed records.
struct FloatGatherArrays {
    const uint32_t* face = nullptr;
    const glm::dvec2* bary = nullptr;
    const double* height = nullptr;
    const PackedBindingVertex* packed = nullptr;  // used when not null
    const glm::uvec3* tri = nullptr;
    const FloatCorner* corner = nullptr;
};

// Vertex i's float32 inputs from either layout.
inline PackedBindingVertex floatInputs(const FloatGatherArrays& a, size_t i) {
    if (a.packed) return a.packed[i];
    return {a.face[i], float(a.bary[i].x), float(a.bary[i].y), float(a.height[i])};
}

// The float32 evaluation of one vertex, the definition the AVX2 kernel reproduces bit for bit:
// b0 = (1 - b1) - b2; per component p = (b0 x0 + b1 x1) + b2 x2 and likewise the normal;
// len2 = (nx nx + ny ny) + nz nz; n = n (1 / sqrt(len2)), or (0, 0, 1) when len2 is not
// positive; P = p + h n. Every operation is a correctly rounded float32 operation (no fused
// multiply-add: the build enables none), so the result does not depend on the compiler's choice
// of instructions.
inline glm::vec3 gatherFloat(const FloatGatherArrays& a, size_t i) {
    const PackedBindingVertex v = floatInputs(a, i);
    const glm::uvec3 f = a.tri[v.face];
    const FloatCorner &c0 = a.corner[f.x], &c1 = a.corner[f.y], &c2 = a.corner[f.z];
    const float b0 = (1.0f - v.b1) - v.b2;
    float p[3], n[3];
    for (int k = 0; k < 3; ++k) {
        p[k] = (b0 * c0.p[k] + v.b1 * c1.p[k]) + v.b2 * c2.p[k];
        n[k] = (b0 * c0.n[k] + v.b1 * c1.n[k]) + v.b2 * c2.n[k];
    }
    const float len2 = (n[0] * n[0] + n[1] * n[1]) + n[2] * n[2];
    if (len2 > 0.0f) {
        const float inv = 1.0f / std::sqrt(len2);
        for (float& x : n) x *= inv;
    } else {
        n[0] = n[1] = 0.0f;
        n[2] = 1.0f;
    }
    return {p[0] + v.height * n[0], p[1] + v.height * n[1], p[2] + v.height * n[2]};
}

// The mesh as float32 corners relative to `origin` (in parallel).
std::unique_ptr<FloatCorner[]> floatCorners(const std::vector<glm::dvec3>& positions,
                                            const std::vector<glm::dvec3>& normals, glm::dvec3 origin);

// True when this CPU runs the AVX2 kernel (util::avx2Kernels).
bool evaluateFloatSimdAvailable();

// Vertices [begin, end) eight at a time: out[i] = gatherFloat(a, i) bit for bit. Returns the
// first vertex not done (fewer than eight remain); writes nothing outside [begin, returned
// end). Call only when evaluateFloatSimdAvailable().
size_t evaluateFloatSimd(const FloatGatherArrays& a, size_t begin, size_t end, glm::vec3* out);

}  // namespace knit::impl
