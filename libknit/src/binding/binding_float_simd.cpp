// binding_float_simd.cpp — gatherFloat (binding_float.hpp) eight vertices at a time in AVX2
// (x86-64 only, chosen at run time: the functions carry their own target attribute, the rest of
// the build stays SSE2).
//
// Per group of eight vertices: (1) their barycentrics and heights as eight-lane registers (from
// the binding's double arrays, rounded as the scalar code rounds them, or from packed records
// by a 4x4 transpose per half); (2) per vertex, its three corners (x y z 0 | nx ny nz 0, one
// 32-byte load each) weighted by its broadcast barycentrics: position and normal in one
// register; (3) a transpose to x, y, z registers of the eight positions and eight normals;
// (4) the normals' lengths, one square root and one division for all eight, P = p + h n;
// (5) P back to 24 consecutive floats by three lane permutations per output register.
// Multiplies, adds, a square root and a division, each correctly rounded and in the scalar
// order, and no FMA (the target is "avx2", not "fma"): bit for bit gatherFloat.
#include <algorithm>
#include <cstdint>

#include "binding_float.hpp"
#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include <immintrin.h>
#endif

namespace knit::impl {

#if KNIT_HAVE_AVX2_KERNELS
namespace {

// Eight vertices' inputs, one per lane.
struct Weights {
    __m256 b0, b1, b2, h;
};

KNIT_AVX2 inline __m256 halves(__m128 lo, __m128 hi) { return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1); }

// From the binding's arrays: (b1, b2) pairs of doubles rounded to float32 and split.
KNIT_AVX2 inline Weights binaryWeights(const FloatGatherArrays& a, size_t i) {
    const double* b = &a.bary[i].x;
    const __m128 q0 = _mm256_cvtpd_ps(_mm256_loadu_pd(b)), q1 = _mm256_cvtpd_ps(_mm256_loadu_pd(b + 4));
    const __m128 q2 = _mm256_cvtpd_ps(_mm256_loadu_pd(b + 8)), q3 = _mm256_cvtpd_ps(_mm256_loadu_pd(b + 12));
    const __m256 lo = halves(q0, q2), hi = halves(q1, q3);  // (b1 b2 b1 b2) of vertices 0 1 2 3 | 4 5 6 7 in pairs
    Weights w;
    w.b1 = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
    w.b2 = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
    w.h = halves(_mm256_cvtpd_ps(_mm256_loadu_pd(a.height + i)), _mm256_cvtpd_ps(_mm256_loadu_pd(a.height + i + 4)));
    return w;
}

// Records j and j + 4 (face b1 b2 h, as float lanes) in one register.
KNIT_AVX2 inline __m256 recordPair(const float* r, int j) {
    return halves(_mm_loadu_ps(r + 4 * j), _mm_loadu_ps(r + 4 * (j + 4)));
}

// From packed records: a 4x4 transpose within each half of the record pairs.
KNIT_AVX2 inline Weights packedWeights(const FloatGatherArrays& a, size_t i) {
    const float* r = reinterpret_cast<const float*>(a.packed + i);
    const __m256 r0 = recordPair(r, 0), r1 = recordPair(r, 1), r2 = recordPair(r, 2), r3 = recordPair(r, 3);
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);  // f f b1 b1, b2 b2 h h
    const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
    Weights w;
    w.b1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    w.b2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    w.h = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    return w;
}

template <bool kPacked>
KNIT_AVX2 inline uint32_t faceOf(const FloatGatherArrays& a, size_t i) {
    if constexpr (kPacked) return a.packed[i].face;
    return a.face[i];
}

// Vertex i's interpolated position and normal (x y z 0 | nx ny nz 0), the weights read from
// lane j of the stored group weights.
template <bool kPacked>
KNIT_AVX2 inline __m256 interpolate(const FloatGatherArrays& a, size_t i, const float* b0, const float* b1,
                                    const float* b2) {
    const glm::uvec3 f = a.tri[faceOf<kPacked>(a, i)];
    const __m256 c0 = _mm256_load_ps(a.corner[f.x].p), c1 = _mm256_load_ps(a.corner[f.y].p);
    const __m256 c2 = _mm256_load_ps(a.corner[f.z].p);
    const __m256 s0 = _mm256_mul_ps(_mm256_broadcast_ss(b0), c0), s1 = _mm256_mul_ps(_mm256_broadcast_ss(b1), c1);
    return _mm256_add_ps(_mm256_add_ps(s0, s1), _mm256_mul_ps(_mm256_broadcast_ss(b2), c2));
}

// Four vertices' (x y z 0 | nx ny nz 0) as x, y, z lanes: (x0 x1 x2 x3 | nx0 nx1 nx2 nx3) etc.
struct Quad {
    __m256 x, y, z;
};
KNIT_AVX2 inline Quad transpose4(__m256 v0, __m256 v1, __m256 v2, __m256 v3) {
    const __m256 t0 = _mm256_unpacklo_ps(v0, v1), t1 = _mm256_unpackhi_ps(v0, v1);  // x x y y, z z 0 0
    const __m256 t2 = _mm256_unpacklo_ps(v2, v3), t3 = _mm256_unpackhi_ps(v2, v3);
    return {_mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0)), _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2)),
            _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0))};
}

// One output register of storePoints: the floats of x, y, z at the lanes `ix`, y where
// kMaskY has a bit, z where kMaskZ has one.
template <int kMaskY, int kMaskZ>
KNIT_AVX2 inline __m256 interleave(__m256 x, __m256 y, __m256 z, __m256i ix) {
    const __m256 px = _mm256_permutevar8x32_ps(x, ix), py = _mm256_permutevar8x32_ps(y, ix);
    const __m256 pz = _mm256_permutevar8x32_ps(z, ix);
    return _mm256_blend_ps(_mm256_blend_ps(px, py, kMaskY), pz, kMaskZ);
}

// Eight x, y, z lanes stored as eight consecutive points (24 floats): output float k of
// register r is point (8 r + k) / 3's coordinate (8 r + k) % 3, i.e. x y z x y z x y,
// z x y z x y z x and y z x y z x y z.
KNIT_AVX2 inline void storePoints(float* out, __m256 x, __m256 y, __m256 z) {
    _mm256_storeu_ps(out, interleave<0b10010010, 0b00100100>(x, y, z, _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2)));
    _mm256_storeu_ps(out + 8, interleave<0b00100100, 0b01001001>(x, y, z, _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5)));
    _mm256_storeu_ps(out + 16, interleave<0b01001001, 0b10010010>(x, y, z, _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7)));
}

// A group of eight vertices between the two phases of a chunk: interpolated positions and
// normals as x, y, z lanes, the heights.
struct Group {
    __m256 px, py, pz, nx, ny, nz, h;
};

// Phase 1 for the eight vertices from i: weights, corners, interpolation, transpose.
template <bool kPacked>
KNIT_AVX2 inline void interpolateGroup(const FloatGatherArrays& a, size_t i, Group& g) {
    Weights w = kPacked ? packedWeights(a, i) : binaryWeights(a, i);
    w.b0 = _mm256_sub_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), w.b1), w.b2);
    alignas(32) float b[3][8];
    _mm256_store_ps(b[0], w.b0);
    _mm256_store_ps(b[1], w.b1);
    _mm256_store_ps(b[2], w.b2);
    __m256 v[8];
    for (int j = 0; j < 8; ++j) v[j] = interpolate<kPacked>(a, i + j, b[0] + j, b[1] + j, b[2] + j);
    const Quad lo = transpose4(v[0], v[1], v[2], v[3]), hi = transpose4(v[4], v[5], v[6], v[7]);
    // The low halves hold the positions, the high halves the normals.
    g.px = _mm256_permute2f128_ps(lo.x, hi.x, 0x20);
    g.py = _mm256_permute2f128_ps(lo.y, hi.y, 0x20);
    g.pz = _mm256_permute2f128_ps(lo.z, hi.z, 0x20);
    g.nx = _mm256_permute2f128_ps(lo.x, hi.x, 0x31);
    g.ny = _mm256_permute2f128_ps(lo.y, hi.y, 0x31);
    g.nz = _mm256_permute2f128_ps(lo.z, hi.z, 0x31);
    g.h = w.h;
}

// Phase 2: normalize (one square root and one division for eight), P = p + h n, store.
KNIT_AVX2 inline void finishGroup(const Group& g, float* out) {
    const __m256 len2 =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(g.nx, g.nx), _mm256_mul_ps(g.ny, g.ny)), _mm256_mul_ps(g.nz, g.nz));
    const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(len2));
    const __m256 ok = _mm256_cmp_ps(len2, _mm256_setzero_ps(), _CMP_GT_OQ);
    const __m256 ux = _mm256_and_ps(ok, _mm256_mul_ps(g.nx, inv)), uy = _mm256_and_ps(ok, _mm256_mul_ps(g.ny, inv));
    const __m256 uz = _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_mul_ps(g.nz, inv), ok);
    storePoints(out, _mm256_add_ps(g.px, _mm256_mul_ps(g.h, ux)), _mm256_add_ps(g.py, _mm256_mul_ps(g.h, uy)),
                _mm256_add_ps(g.pz, _mm256_mul_ps(g.h, uz)));
}

// Vertices the input streams are prefetched ahead of the chunk being interpolated (measured: the
// hardware prefetcher alone left the loads of the streamed barycentrics among the hottest
// instructions); a chunk of 32 vertices reads 8 lines of barycentrics or records, 4 of heights
// and 2 of faces.
constexpr size_t kPrefetchVertices = 256;

template <class T>
KNIT_AVX2 inline void prefetchAhead(const T* p, int lines) {
    const char* ahead = reinterpret_cast<const char*>(p + kPrefetchVertices);
    for (int l = 0; l < lines; ++l) _mm_prefetch(ahead + 64 * l, _MM_HINT_T0);
}

// The input lines of the 32 vertices kPrefetchVertices after i.
template <bool kPacked>
KNIT_AVX2 inline void prefetchInputs(const FloatGatherArrays& a, size_t i) {
    if constexpr (kPacked) {
        prefetchAhead(a.packed + i, 8);
    } else {
        prefetchAhead(a.bary + i, 8);
        prefetchAhead(a.height + i, 4);
        prefetchAhead(a.face + i, 2);
    }
}

// Groups per chunk: a chunk's interpolations first, then its square roots and divisions, which
// do not depend on each other and overlap (group by group, each stalled on its own).
constexpr size_t kChunkGroups = 4;

template <bool kPacked>
KNIT_AVX2 size_t evaluateGroups(const FloatGatherArrays& a, size_t begin, size_t end, glm::vec3* out) {
    Group g[kChunkGroups];
    size_t i = begin;
    while (i + 8 <= end) {
        const size_t groups = std::min(kChunkGroups, (end - i) / 8);
        for (size_t k = 0; k < groups; ++k) interpolateGroup<kPacked>(a, i + 8 * k, g[k]);
        if (i + kPrefetchVertices + 32 <= end) prefetchInputs<kPacked>(a, i);  // within the range only
        for (size_t k = 0; k < groups; ++k, i += 8) finishGroup(g[k], &out[i].x);
    }
    return i;
}

}  // namespace

bool evaluateFloatSimdAvailable() { return util::avx2Kernels(); }

size_t evaluateFloatSimd(const FloatGatherArrays& a, size_t begin, size_t end, glm::vec3* out) {
    return a.packed ? evaluateGroups<true>(a, begin, end, out) : evaluateGroups<false>(a, begin, end, out);
}

#else  // not x86-64 with GCC or Clang: the scalar loop only

bool evaluateFloatSimdAvailable() { return false; }
size_t evaluateFloatSimd(const FloatGatherArrays&, size_t begin, size_t, glm::vec3*) { return begin; }

#endif

}  // namespace knit::impl
