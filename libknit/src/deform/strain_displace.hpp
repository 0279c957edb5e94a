// strain_displace.hpp (internal) — the strain deformer's last phase at the mesh's UV vertices
// (StrainLookupSite::MeshVertices): per yarn vertex, its triangle's corner rows of per-UV-vertex
// displacements interpolated and added to the gathered point. The scalar reference here; four
// yarn vertices at a time, fused into the binding's AVX2 gather, in strain_displace_simd.cpp
// (bit for bit the same).
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "binding/binding_evaluate_simd.hpp"

namespace knit::impl {

// Per yarn vertex flags (a triangle's: its corners' flags or'ed, or degenerate).
enum : uint8_t { kStrainZero = 0, kStrainMoved = 1, kStrainClamped = 2, kStrainDegenerate = 4 };

// Per triangle: where its corners' rows start in the displacements (UV vertex times cell
// vertices) and what its yarn vertices are.
struct StrainCorners {
    uint32_t row[3];
    uint8_t flag;
};

// What the displacement reads: per triangle its corners, per UV vertex and cell vertex the
// displacement through F (x, y, z) and along the normal (w), per yarn vertex its cell vertex.
struct StrainRows {
    const StrainCorners* corners;
    const glm::dvec4* d;
    const uint32_t* cellVertex;
};

// The displacement of a yarn vertex (triangle `face`, barycentrics (b1, b2), normal n) as cell
// vertex v, into `out`; returns its triangle's flag (no displacement unless kStrainMoved).
inline uint8_t strainDisplacement(const StrainRows& s, uint32_t face, const glm::dvec2& bary, uint32_t v,
                                  const glm::dvec3& n, glm::dvec3& out) {
    const StrainCorners& c = s.corners[face];
    if (!(c.flag & kStrainMoved)) return c.flag;
    const double b1 = bary.x, b2 = bary.y, b0 = 1.0 - b1 - b2;
    const glm::dvec4 e = b0 * s.d[c.row[0] + v] + b1 * s.d[c.row[1] + v] + b2 * s.d[c.row[2] + v];
    out = glm::dvec3(e) + e.w * n;
    return c.flag;
}

// Vertices [begin, end) four at a time: the gather (evaluateDoubleSimd) with each moved
// vertex's strainDisplacement (as its own cell vertex) added, P[i] = p + e; bit for bit
// BindingGather followed by strainDisplacement. Returns the first vertex not done; call only
// when evaluateSimdAvailable().
size_t evaluateDisplacedSimd(const GatherArrays& a, const StrainRows& s, size_t begin, size_t end, glm::dvec3* P,
                             glm::dvec3* N);

}  // namespace knit::impl
