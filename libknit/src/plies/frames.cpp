// frames.cpp — rotation-minimizing frames by double reflection (Wang, Juttler, Zheng, Liu 2008).
//
// Per curve:
//   1. unit segment directions; zero-length segments (repeated points) reuse the nearest real
//      direction on each side, so all copies of a repeated point share one tangent and frame;
//   2. point tangents = normalized sum of the adjacent segment directions (closed curves wrap);
//      at an exact hairpin (the sum vanishes) the outgoing direction is used;
//   3. seed normal = seedNormals[first point] projected perpendicular to the tangent, or the
//      coordinate axis least aligned with the tangent when there is no usable seed;
//   4. double-reflection transport point to point (per block of steps, the parts that do not
//      depend on the normal first: frames_transport.cpp; skipping the first reflection on
//      zero-length segments, the second when the tangent is unchanged), re-orthonormalized
//      every 16 steps and at the end so no drift accumulates; turns of more than 90 degrees
//      between two samples (unresolved hairpins, tangent reversals) project the normal
//      instead (see transport);
//   5. closed curves: transport once more across the closing segment, measure the signed
//      mismatch angle about the first tangent with atan2 and rotate every frame by the angle
//      times its arc-length fraction, so the frame closes with no jump.
// Curves are independent; TBB splits the curve list, so results do not depend on threads.
#include "knit/frames.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "frames_curve.hpp"
#include "frames_transport.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/csr.hpp"
#include "util/math.hpp"
#include "util/simd.hpp"

namespace knit {
namespace {

using glm::dvec3;

// Rotates r (perpendicular to unit t) about t by the angle with cosine c and sine s.
dvec3 rotateAbout(const dvec3& r, const dvec3& t, double c, double s) { return c * r + s * glm::cross(t, r); }

// A segment is treated as zero-length when it is below the floating-point resolution of its
// end points' coordinates (squared lengths compared; cheap and scale-aware).
bool zeroSegment(const dvec3& a, const dvec3& b, const dvec3& v) {
    constexpr double k = 64.0 * DBL_EPSILON;
    return glm::dot(v, v) <= k * k * std::max(glm::dot(a, a), glm::dot(b, b));
}

// One double-reflection step: frame (t0, r0) at x0 to the point x1 with tangent t1. The result
// is re-orthonormalized against t1 when `renormalize` is set (every few steps: the
// reflections are orthogonal, so drift between renormalizations stays at rounding level).
// A turn of more than 90 degrees between two samples (a hairpin the polyline does not resolve,
// or an exact tangent reversal) has no meaningful rotation-minimizing transport; there the
// normal is projected onto the new normal plane instead, which keeps it as close as possible
// to the previous one (dot > 0, no flip; unchanged at an exact reversal).
inline dvec3 transport(const dvec3& x0, const dvec3& t0, const dvec3& r0, const dvec3& x1, const dvec3& t1,
                       bool renormalize = true) {
    if (glm::dot(t0, t1) < 0.0) {
        const dvec3 p = r0 - glm::dot(r0, t1) * t1;
        const double len = glm::length(p);
        if (len > 1e-6) return p / len;
    }
    const dvec3 v1 = x1 - x0;
    dvec3 rL = r0, tL = t0;
    if (!zeroSegment(x0, x1, v1)) {
        const double a1 = 2.0 / glm::dot(v1, v1);
        rL = r0 - (a1 * glm::dot(v1, r0)) * v1;
        tL = t0 - (a1 * glm::dot(v1, t0)) * v1;
    }
    const dvec3 v2 = t1 - tL;
    const double c2 = glm::dot(v2, v2);
    dvec3 r1 = c2 > 1e-24 ? rL - ((2.0 / c2) * glm::dot(v2, rL)) * v2 : rL;  // straight run: r1 = rL
    if (!renormalize) return r1;
    r1 -= glm::dot(r1, t1) * t1;
    const double len = glm::length(r1);
    return len > 1e-6 ? r1 / len : util::anyPerpendicular(t1);
}

// v turned by the smallest rotation taking unit a onto unit b (about a x b); unchanged when a
// and b are opposite (no unique smallest rotation: the caller's projection decides).
inline dvec3 minimalRotation(const dvec3& a, const dvec3& b, const dvec3& v) {
    const dvec3 w = glm::cross(a, b);
    const double c = glm::dot(a, b);
    if (1.0 + c < 1e-9) return v;
    return v + glm::cross(w, v) + glm::cross(w, glm::cross(w, v)) / (1.0 + c);
}

}  // namespace

void curveFrames(const glm::dvec3* x, size_t n, bool closed, const glm::dvec3* seedNormal, glm::dvec3* T, glm::dvec3* N,
                 const FrameOptions& options, const glm::dvec3* seedTangent, float* floatScratch) {
    if (n == 0) return;
    const bool simd = util::avx2Kernels();
    // Float32 transport (AVX2 only): the curve's float copies, filled by steps 1 and 2.
    std::vector<float> ownScratch;
    impl::FloatCurve fc{};
    const bool useFloat = simd && options.precision == FramePrecision::Float32 && n >= 2;
    if (useFloat) {
        if (!floatScratch) ownScratch.resize(6 * n), floatScratch = ownScratch.data();
        for (int c = 0; c < 3; ++c) fc.v[c] = floatScratch + c * n, fc.t[c] = floatScratch + (3 + c) * n;
    }
    const impl::FloatCurve* f = useFloat ? &fc : nullptr;

    // Seed candidate (the surface normal at the first point), if usable.
    dvec3 seed(0.0);
    bool haveSeed = false;
    if (seedNormal) {
        seed = *seedNormal;
        const double len = glm::length(seed);
        haveSeed = util::finite(seed) && len > 0.0;
        if (haveSeed) seed /= len;
    }

    // Step 1: unit segment directions (zero for zero-length segments), stored in the output
    // arrays before they are needed: N[k] = last real direction at or before segment k (filled
    // forward), T[k] = next real direction at or after k (filled backward), so all copies of a
    // repeated point get the same tangent (cyclically on closed curves; zero = none on open).
    const size_t segs = n < 2 ? 0 : (closed ? n : n - 1);
    size_t firstValid = segs, lastValid = segs;
    bool anyZero = false;
    const size_t simdSegments = impl::unitDirections(x, n, T, N, simd, f);  // [0, simdSegments): real directions
    if (simdSegments > 0) firstValid = 0, lastValid = simdSegments - 1;
    for (size_t k = simdSegments; k < segs; ++k) {
        const dvec3& p = x[k];
        const dvec3& q = x[k + 1 == n ? 0 : k + 1];
        const dvec3 v = q - p;
        if (zeroSegment(p, q, v)) {
            T[k] = N[k] = dvec3(0.0);
            anyZero = true;
        } else {
            T[k] = N[k] = v / glm::length(v);
            if (f && k + 1 < n)
                for (int c = 0; c < 3; ++c) fc.v[c][k] = static_cast<float>(v[c]);
            if (firstValid == segs) firstValid = k;
            lastValid = k;
        }
    }
    if (firstValid == segs) {
        // No direction at all (one point, or all points equal): any frame is a valid one.
        const dvec3 t = haveSeed ? util::anyPerpendicular(seed) : dvec3(1.0, 0.0, 0.0);
        const dvec3 r = haveSeed ? seed : util::anyPerpendicular(t);
        for (size_t i = 0; i < n; ++i) {
            T[i] = t;
            N[i] = r;
        }
        return;
    }
    const dvec3 zero(0.0);
    for (size_t j = 1; j < segs && anyZero; ++j) {  // forward fill of the previous directions (N)
        const size_t k = closed ? (firstValid + j) % segs : j;
        if (!closed && k <= firstValid) continue;
        if (N[k] == zero) N[k] = N[(k + segs - 1) % segs];
    }
    for (size_t j = 1; j < segs && anyZero; ++j) {  // backward fill of the next directions (T)
        const size_t k = closed ? (lastValid + segs - j) % segs : segs - 1 - j;
        if (!closed && k >= lastValid) continue;
        if (T[k] == zero) T[k] = T[(k + 1) % segs];
    }

    // (Both fills only replace zero directions: without a zero-length segment they are skipped.)
    // Step 2: point tangents from the nearest real directions on either side (in place: point
    // i reads N[i-1] and T[i], which are still directions when it is computed).
    // Without zero-length segments the points between the first and the last segment have a
    // real direction on both sides: four at a time in AVX2 (frames_transport.cpp).
    for (size_t i = 0; i < n; ++i) {
        if (i == 1 && !anyZero) {
            i = impl::pointTangents(N, T, 1, segs, simd, f);
            if (i >= n) break;
        }
        const dvec3 prev = (closed || i > 0) ? N[(i + segs - 1) % segs] : zero;
        const dvec3 next = i < segs ? T[i] : zero;
        if (prev == zero) {
            T[i] = next;
        } else if (next == zero) {
            T[i] = prev;
        } else {
            const dvec3 sum = prev + next;
            const double len = glm::length(sum);
            T[i] = len > 1e-6 ? sum / len : next;  // hairpin: tangent reversal, take outgoing
        }
        if (f)
            for (int c = 0; c < 3; ++c) fc.t[c][i] = static_cast<float>(T[i][c]);
    }
    if (anyZero) f = nullptr;  // the float kernel assumes real segments: the double path

    // Step 3: seed normal (transported from seedTangent onto T[0] first, when given).
    {
        dvec3 r(0.0);
        double len = 0.0;
        if (haveSeed && seedTangent) seed = minimalRotation(*seedTangent, T[0], seed);
        if (haveSeed) {
            r = seed - glm::dot(seed, T[0]) * T[0];
            len = glm::length(r);
        }
        N[0] = len > 1e-6 ? r / len : util::anyPerpendicular(T[0]);
    }

    // Step 4: double-reflection transport, a block of steps at a time: each step's two
    // reflections as one matrix (frames_transport.cpp; four steps at a time in AVX2), then the
    // chain of the normal through them. Steps that renormalize or reverse the tangent run
    // transport() whole. The matrix rounds differently from the two reflections one after the
    // other (relative differences ~1e-16 per step, undone by the renormalization every 16 steps;
    // docs/memory-limit.md) and makes the chain four times shorter. The chain is bound by its
    // latency, so the next block's matrices are computed during it, a group of four steps (eight
    // with FramePrecision::Float32: float32 lanes from the copies steps 1 and 2 made) before the
    // chain runs through the same group (they do not depend on the normal: the out-of-order core
    // overlaps the two). The carried normal stays in registers (r): read back from N, it would
    // wait on its own store each step.
    const size_t steps = n - 1;
    impl::TransportBlock blocks[2];
    const size_t stride = f ? 8 : 4;  // steps per register
    if (steps > 0) impl::transportCoefficients(x, T, 0, std::min(impl::kTransportBlock, steps), blocks[0], simd, 0, f);
    dvec3 r = N[0];
    for (size_t first = 0, b = 0; first < steps; first += impl::kTransportBlock, b ^= 1) {
        const impl::TransportBlock& block = blocks[b];
        const size_t count = std::min(impl::kTransportBlock, steps - first);
        const size_t nextFirst = first + impl::kTransportBlock;
        const size_t nextCount = nextFirst < steps ? std::min(impl::kTransportBlock, steps - nextFirst) : 0;
        for (size_t k0 = 0; k0 < count; k0 += stride) {
            if (k0 < nextCount)
                impl::transportCoefficients(x, T, nextFirst, std::min(k0 + stride, nextCount), blocks[b ^ 1], simd, k0,
                                            f);
            // The chain through this group's steps: no call inside, so r stays in registers
            // (a call in the loop made the compiler keep r on the stack, a store and a load per step).
            const size_t end = std::min(k0 + stride, count);
            for (size_t k = k0; k < end; ++k) {
                const size_t i = first + k;
                const bool renormalize = (i & 15u) == 15u || i + 2 == n;
                if (renormalize || block.reversal[k]) {
                    r = transport(x[i], T[i], r, x[i + 1], T[i + 1], renormalize);
                } else {
                    const auto row = [&](int e) {
                        return (block.m[e][k] * r.x + block.m[e + 1][k] * r.y) + block.m[e + 2][k] * r.z;
                    };
                    r = dvec3(row(0), row(3), row(6));
                }
                N[i + 1] = r;
            }
        }
    }

    // Step 5: close loops by spreading the signed closing angle along arc length.
    if (closed && options.closeLoops && n >= 2) {
        const dvec3 rEnd = transport(x[n - 1], T[n - 1], N[n - 1], x[0], T[0]);
        const double phi = std::atan2(glm::dot(T[0], glm::cross(rEnd, N[0])), glm::dot(rEnd, N[0]));
        double total = 0.0;
        for (size_t k = 0; k < n; ++k) total += glm::length(x[(k + 1) % n] - x[k]);
        if (total > 0.0 && phi != 0.0) {
            double s = 0.0;
            for (size_t i = 1; i < n; ++i) {
                s += glm::length(x[i] - x[i - 1]);
                const double a = phi * (s / total);
                const dvec3 r = rotateAbout(N[i], T[i], std::cos(a), std::sin(a));
                N[i] = glm::normalize(r - glm::dot(r, T[i]) * T[i]);
            }
        }
    }
}

Frames rotationMinimizingFrames(const Polylines& curves, const std::vector<glm::dvec3>* seedNormals,
                                const FrameOptions& options) {
    // Validate first: the per-curve loops do not throw.
    if (!util::validOffsets(curves.offsets, curves.curveCount(), curves.pointCount()))
        throw Error("ply frames: the curve offsets do not match the curve points");
    if (seedNormals && seedNormals->size() != curves.pointCount())
        throw Error("ply frames: " + std::to_string(seedNormals->size()) + " surface normals for " +
                    std::to_string(curves.pointCount()) + " curve points");
    for (size_t c = 0; c < curves.curveCount(); ++c)
        for (uint32_t i = curves.begin(c); i < curves.end(c); ++i)
            if (!util::finite(curves.points[i]))
                throw Error("ply frames: curve " + std::to_string(c) + " point " + std::to_string(i - curves.begin(c)) +
                            " is not finite");

    Frames frames;
    frames.tangent.resize(curves.pointCount());
    frames.normal.resize(curves.pointCount());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, curves.curveCount()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t c = r.begin(); c < r.end(); ++c) {
            const uint32_t b = curves.begin(c);
            curveFrames(curves.points.data() + b, curves.size(c), curves.isClosed(c),
                        seedNormals ? seedNormals->data() + b : nullptr, frames.tangent.data() + b,
                        frames.normal.data() + b, options);
        }
    });
    return frames;
}

}  // namespace knit
