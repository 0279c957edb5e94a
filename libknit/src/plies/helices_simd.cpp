// helices_simd.cpp — helicesCosSin and helicesStreamed (helices_simd.hpp): per group of four
// centre points, the points, tangents and normals as x, y, z registers, B = T x N as glm::cross,
// then per ply c = ct cos_i - st sin_i, s = st cos_i + ct sin_i, radial = c N + s B,
// P = X + R radial, stored back as four points. No FMA (target "avx2"): helixPoint's results bit
// for bit.
#include "helices_simd.hpp"

#include <cstdint>

#include <glm/geometric.hpp>

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
using lanes::stream4;

// Four centre points from j: X, N, B = T x N and the phase's cosine and sine.
struct Group {
    Lanes x, n, b;
    __m256d ct, st;
};

KNIT_AVX2 inline Group loadGroup(const HelixInput& in, size_t j) {
    Group g;
    g.x = load4(in.X + j);
    g.n = load4(in.N + j);
    const Lanes t = load4(in.T + j);
    const Lanes& n = g.n;
    // glm::cross(t, n) = (t.y n.z - n.y t.z, t.z n.x - n.z t.x, t.x n.y - n.x t.y)
    g.b = {_mm256_sub_pd(_mm256_mul_pd(t.y, n.z), _mm256_mul_pd(n.y, t.z)),
           _mm256_sub_pd(_mm256_mul_pd(t.z, n.x), _mm256_mul_pd(n.z, t.x)),
           _mm256_sub_pd(_mm256_mul_pd(t.x, n.y), _mm256_mul_pd(n.x, t.y))};
    // (cos, sin) of four points: c0 s0 c1 s1 | c2 s2 c3 s3 -> c0 c1 c2 c3, s0 s1 s2 s3.
    const __m256d p01 = _mm256_loadu_pd(&in.phase[j].x), p23 = _mm256_loadu_pd(&in.phase[j + 2].x);
    g.ct = _mm256_permute4x64_pd(_mm256_unpacklo_pd(p01, p23), 0xD8);
    g.st = _mm256_permute4x64_pd(_mm256_unpackhi_pd(p01, p23), 0xD8);
    return g;
}

// Ply i of a group: its radial directions and points.
KNIT_AVX2 inline void plyOfGroup(const Group& g, const HelixInput& in, uint32_t i, Lanes& radial, Lanes& point) {
    const __m256d cp = _mm256_set1_pd(in.cosPly[i]), sp = _mm256_set1_pd(in.sinPly[i]), R = _mm256_set1_pd(in.R);
    const __m256d c = _mm256_sub_pd(_mm256_mul_pd(g.ct, cp), _mm256_mul_pd(g.st, sp));
    const __m256d s = _mm256_add_pd(_mm256_mul_pd(g.st, cp), _mm256_mul_pd(g.ct, sp));
    radial = {_mm256_add_pd(_mm256_mul_pd(c, g.n.x), _mm256_mul_pd(s, g.b.x)),
              _mm256_add_pd(_mm256_mul_pd(c, g.n.y), _mm256_mul_pd(s, g.b.y)),
              _mm256_add_pd(_mm256_mul_pd(c, g.n.z), _mm256_mul_pd(s, g.b.z))};
    point = {_mm256_add_pd(g.x.x, _mm256_mul_pd(R, radial.x)), _mm256_add_pd(g.x.y, _mm256_mul_pd(R, radial.y)),
             _mm256_add_pd(g.x.z, _mm256_mul_pd(R, radial.z))};
}

KNIT_AVX2 size_t helicesAvx2(const HelixInput& in, glm::dvec3* P, glm::dvec3* D) {
    size_t j = 0;
    for (; j + 4 <= in.m; j += 4) {
        const Group g = loadGroup(in, j);
        for (uint32_t i = 0; i < in.plies; ++i) {
            Lanes radial, point;
            plyOfGroup(g, in, i, radial, point);
            store4(P + i * in.m + j, point);
            if (D) store4(D + i * in.m + j, radial);
        }
    }
    return j;
}

// Ply i's points [j0, j1) one at a time (the heads and tails of the streamed ranges).
void scalarRange(const HelixInput& in, uint32_t i, size_t j0, size_t j1, glm::dvec3* P, glm::dvec3* D) {
    for (size_t j = j0; j < j1; ++j)
        helixPoint(in.X[j], in.N[j], glm::cross(in.T[j], in.N[j]), in.phase[j].x, in.phase[j].y, in.cosPly[i],
                   in.sinPly[i], in.R, P[i * in.m + j], D ? &D[i * in.m + j] : nullptr);
}

// Per ply (its points are contiguous), groups of four from the first point whose address is
// 32-byte aligned (four points are 96 bytes, so every group after it is too), written with
// streaming stores; the few points before and after one at a time.
KNIT_AVX2 void helicesStreamedAvx2(const HelixInput& in, size_t head0, glm::dvec3* P, glm::dvec3* D) {
    for (uint32_t i = 0; i < in.plies; ++i) {
        // Aligned points are those i m + j = head0 (mod 4): 24 bytes a point, 96 four.
        size_t head = (head0 + 4 - (i * in.m) % 4) % 4;
        head = head < in.m ? head : in.m;
        scalarRange(in, i, 0, head, P, D);
        size_t j = head;
        for (; j + 4 <= in.m; j += 4) {
            const Group g = loadGroup(in, j);
            Lanes radial, point;
            plyOfGroup(g, in, i, radial, point);
            stream4(P + i * in.m + j, point);
            if (D) stream4(D + i * in.m + j, radial);
        }
        scalarRange(in, i, j, in.m, P, D);
    }
    _mm_sfence();
}

// Points from p to the first 32-byte aligned address (0 to 3), or 4 when p is not 8-byte aligned.
size_t pointsToAlignment(const glm::dvec3* p) {
    const auto a = reinterpret_cast<uintptr_t>(p);
    if (a % 8 != 0) return 4;
    size_t k = 0;
    while ((a + 24 * k) % 32 != 0) ++k;
    return k;
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

bool helicesStreamed(const HelixInput& in, glm::dvec3* P, glm::dvec3* D, bool simd) {
#if KNIT_HAVE_AVX2_KERNELS
    const size_t head = pointsToAlignment(P);
    if (!simd || head > 3 || (D && pointsToAlignment(D) != head)) return false;
    helicesStreamedAvx2(in, head, P, D);
    return true;
#else
    (void)in, (void)P, (void)D, (void)simd;
    return false;
#endif
}

}  // namespace knit::impl
