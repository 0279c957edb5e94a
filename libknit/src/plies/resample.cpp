// resample.cpp — centripetal Catmull-Rom resampling of yarn centrelines.
//
// Conventions (documented here, relied on by makePlies and the tests):
// - Curve i of the output is curve i of the input (1:1, same closed flag), so indices into the
//   yarn list stay valid. A curve that has 0 or 1 distinct points is kept as it is (0 or 1
//   point, no segments); callers decide what to do with it (makePlies emits no plies for it).
// - Consecutive points closer than 1e-12 * spacing are merged (the first one is kept); on a
//   closed curve a last point repeating the first one is merged too.
// - Every remaining input vertex appears in the output bit for bit, in order; new points are
//   inserted between them only.
// - Open ends use the reflected neighbour (p[-1] = 2 p[0] - p[1]), so a straight end stays
//   straight; closed curves wrap around.
#include "knit/resample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "knit/error.hpp"
#include "resample_curve.hpp"
#include "util/checks.hpp"
#include "util/csr.hpp"
#include "util/simd.hpp"

#if KNIT_HAVE_AVX2_KERNELS
#include "simd_lanes.hpp"
#endif

namespace knit {
namespace {

using glm::dvec3;

// One cubic piece p(u) = ((a u + b) u + c) u + d, u in [0, 1], from p1 (u = 0) to p2 (u = 1).
struct Cubic {
    dvec3 a, b, c, d;
    double maxLeg = 0.0;   // longest leg of the Bezier control polygon
    double polygon = 0.0;  // control polygon length (upper bound of the arc length)
    dvec3 eval(double u) const { return ((a * u + b) * u + c) * u + d; }
};

// The reciprocals of the knot intervals and of the sums of two neighbouring ones, which makeCubic
// divides by; neighbouring pieces share three of the five (resampleCurveWithLayout computes each
// once per segment: the same divisions, so the same bits).
struct KnotReciprocals {
    double i01, i12, i23, i02, i13;
};

// Centripetal Catmull-Rom piece between p1 and p2 (Barry-Goldman tangents in Hermite form),
// given the centripetal knot interval t12 = |p2 - p1|^(1/2) and the reciprocals of t01, t12,
// t23, t01 + t12 and t12 + t23 (t_ij = |p_j - p_i|^(1/2)). All intervals are > 0 because
// consecutive duplicates were merged and reflected end points differ from their neighbours.
// Without `bounds` the control polygon's lengths (maxLeg, polygon: three square roots, only
// the adaptive split needs them) are left at 0.
Cubic makeCubic(const dvec3& p0, const dvec3& p1, const dvec3& p2, const dvec3& p3, double t12,
                const KnotReciprocals& r, bool bounds) {
    const double i01 = r.i01, i12 = r.i12, i23 = r.i23, i02 = r.i02, i13 = r.i13;
    const dvec3 d12 = (p2 - p1) * i12;
    const dvec3 m1 = t12 * ((p1 - p0) * i01 - (p2 - p0) * i02 + d12);
    const dvec3 m2 = t12 * (d12 - (p3 - p1) * i13 + (p3 - p2) * i23);
    Cubic c;
    c.a = 2.0 * (p1 - p2) + m1 + m2;
    c.b = 3.0 * (p2 - p1) - 2.0 * m1 - m2;
    c.c = m1;
    c.d = p1;
    if (!bounds) return c;
    constexpr double third = 1.0 / 3.0;
    const double l0 = glm::length(m1) * third;
    const double l1 = glm::length((p2 - p1) - (m1 + m2) * third);
    const double l2 = glm::length(m2) * third;
    c.polygon = l0 + l1 + l2;
    c.maxLeg = std::max(l0, std::max(l1, l2));
    return c;
}

// Reciprocals of a curve's knot intervals, per segment s: inverse[s] = 1 / knot[s] and
// pairInverse[s] = 1 / (knot[s] + knot[next]), next the following segment (wrapping on closed
// curves; on an open curve's last segment, s itself, as the reflected end's interval).
struct KnotInverses {
    const double* inverse;
    const double* pairInverse;
};

// The piece of segment s (from pts[s] to the next point) of a curve of n >= 2 merged points
// with centripetal knot intervals `knot` (one per segment). Open ends use the reflected
// neighbour (same knot interval as the end segment); closed curves wrap around. With `inv`,
// the divisions are read from it (the same values: bit for bit the same piece).
Cubic segmentCubic(const dvec3* pts, const double* knot, size_t n, bool closed, size_t s, bool bounds = true,
                   const KnotInverses* inv = nullptr) {
    const size_t segments = closed ? n : n - 1;
    const size_t s1 = s + 1 == n ? 0 : s + 1;
    const dvec3& p1 = pts[s];
    const dvec3& p2 = pts[s1];
    dvec3 p0, p3;
    size_t k01 = 0, k23 = s;  // the segments whose knot intervals are t01 and t23
    const bool reflectedStart = s == 0 && !closed;
    if (!reflectedStart) {
        const size_t s0 = s == 0 ? n - 1 : s - 1;
        p0 = pts[s0];
        k01 = s == 0 ? segments - 1 : s - 1;
    } else {
        p0 = 2.0 * p1 - p2;
    }
    if (s + 1 < segments || closed) {
        p3 = pts[s1 + 1 == n ? 0 : s1 + 1];
        k23 = s + 1 == segments ? 0 : s + 1;
    } else {
        p3 = 2.0 * p2 - p1;
    }
    const double t01 = knot[k01], t12 = knot[s], t23 = knot[k23];
    KnotReciprocals r;
    if (inv) {
        r = {inv->inverse[k01], inv->inverse[s], inv->inverse[k23],
             reflectedStart ? 1.0 / (t01 + t12) : inv->pairInverse[k01], inv->pairInverse[s]};
    } else {
        r = {1.0 / t01, 1.0 / t12, 1.0 / t23, 1.0 / (t01 + t12), 1.0 / (t12 + t23)};
    }
    return makeCubic(p0, p1, p2, p3, t12, r, bounds);
}

// The centripetal knot interval of the segment from a to b: |b - a|^(1/2), at least 1e-150
// (coincident points get a tiny interval instead of a division by zero).
double knotInterval(const dvec3& a, const dvec3& b) {
    const dvec3 d = b - a;
    return std::max(std::sqrt(std::sqrt(glm::dot(d, d))), 1e-150);
}

#if KNIT_HAVE_AVX2_KERNELS
// knotInterval and its reciprocal for segments s, s + 1, ... four at a time while the group's
// points lie in pts[0, n): knotInterval's operations lane by lane (vmaxpd(1e-150, x) returns
// x unless 1e-150 > x, NaN included, as std::max(x, 1e-150) does), so the same bits. Returns
// the first segment not done.
KNIT_AVX2 size_t knotsAvx2(const dvec3* pts, size_t n, double* knot, double* inverse) {
    size_t s = 0;
    for (; s + 5 <= n; s += 4) {
        const impl::lanes::Lanes d = impl::lanes::sub(impl::lanes::load4(pts + s + 1), impl::lanes::load4(pts + s));
        const __m256d k = _mm256_max_pd(_mm256_set1_pd(1e-150), _mm256_sqrt_pd(_mm256_sqrt_pd(impl::lanes::dot(d, d))));
        _mm256_storeu_pd(knot + s, k);
        _mm256_storeu_pd(inverse + s, _mm256_div_pd(_mm256_set1_pd(1.0), k));
    }
    return s;
}

// The pieces of four interior segments s .. s + 3 (1 <= s, s + 5 < n: no reflected end, no wrap)
// as segmentCubic makes them from the tables (without bounds): makeCubic's operations lane by
// lane, so the same bits; a, b, c of piece s + j in a[j], b[j], c[j] (d is the point pts[s + j]).
struct FourCubics {
    dvec3 a[4], b[4], c[4];
};

KNIT_AVX2 void fourCubicsAvx2(const dvec3* pts, const double* knot, const KnotInverses& inv, size_t s,
                              FourCubics& out) {
    using impl::lanes::add;
    using impl::lanes::Lanes;
    using impl::lanes::load4;
    using impl::lanes::scale;
    using impl::lanes::sub;
    const Lanes p0 = load4(pts + s - 1), p1 = load4(pts + s), p2 = load4(pts + s + 1), p3 = load4(pts + s + 2);
    const __m256d t12 = _mm256_loadu_pd(knot + s);
    const __m256d i01 = _mm256_loadu_pd(inv.inverse + s - 1), i12 = _mm256_loadu_pd(inv.inverse + s),
                  i23 = _mm256_loadu_pd(inv.inverse + s + 1), i02 = _mm256_loadu_pd(inv.pairInverse + s - 1),
                  i13 = _mm256_loadu_pd(inv.pairInverse + s);
    const Lanes e10 = sub(p1, p0), e20 = sub(p2, p0), e21 = sub(p2, p1), e31 = sub(p3, p1), e32 = sub(p3, p2);
    const Lanes d12 = scale(e21, i12);
    const Lanes m1 = scale(add(sub(scale(e10, i01), scale(e20, i02)), d12), t12);
    const Lanes m2 = scale(add(sub(d12, scale(e31, i13)), scale(e32, i23)), t12);
    const Lanes a = add(add(scale(sub(p1, p2), _mm256_set1_pd(2.0)), m1), m2);
    const Lanes b = sub(sub(scale(e21, _mm256_set1_pd(3.0)), scale(m1, _mm256_set1_pd(2.0))), m2);
    impl::lanes::store4(out.a, a);
    impl::lanes::store4(out.b, b);
    impl::lanes::store4(out.c, m1);
}

// 1 / (knot[s] + knot[s + 1]) four at a time while s + 1 < segments; returns the first not done.
KNIT_AVX2 size_t pairInversesAvx2(const double* knot, size_t segments, double* pairInverse) {
    size_t s = 0;
    for (; s + 5 <= segments; s += 4)
        _mm256_storeu_pd(pairInverse + s,
                         _mm256_div_pd(_mm256_set1_pd(1.0),
                                       _mm256_add_pd(_mm256_loadu_pd(knot + s), _mm256_loadu_pd(knot + s + 1))));
    return s;
}
#endif

size_t knotsWithInverses(const dvec3* pts, size_t n, double* knot, double* inverse, bool simd) {
#if KNIT_HAVE_AVX2_KERNELS
    if (simd) return knotsAvx2(pts, n, knot, inverse);
#endif
    (void)pts, (void)n, (void)knot, (void)inverse, (void)simd;
    return 0;
}

size_t pairInverses(const double* knot, size_t segments, double* pairInverse, bool simd) {
#if KNIT_HAVE_AVX2_KERNELS
    if (simd) return pairInversesAvx2(knot, segments, pairInverse);
#endif
    (void)knot, (void)segments, (void)pairInverse, (void)simd;
    return 0;
}

// Normal interpolated linearly between n1 and n2 at fraction f, renormalized. Opposite
// normals (sum ~ 0) fall back to the nearer end's normal.
dvec3 lerpNormal(const dvec3& n1, const dvec3& n2, double f) {
    const dvec3 n = (1.0 - f) * n1 + f * n2;
    const double len = glm::length(n);
    if (len > 1e-12) return n / len;
    return f < 0.5 ? n1 : n2;
}

// Interior parameters u_j = j / k of one piece, with the smallest k (starting from Gravesen's
// arc-length estimate) whose chords are all <= spacing. Uniform parameter steps are nearly
// uniform in arc length on the centripetal spline; a last-resort split with a provably short
// enough step (|p'(u)| <= 3 * maxLeg) guarantees termination.
void splitPiece(const Cubic& cubic, const dvec3& p1, const dvec3& p2, double chord, double spacing,
                std::vector<dvec3>& samples) {
    samples.clear();
    if (cubic.polygon <= spacing) return;                   // arc length <= control polygon: one segment is enough
    const double estimate = 0.5 * (chord + cubic.polygon);  // Gravesen: mean of chord and polygon
    size_t k = static_cast<size_t>(std::ceil(estimate / spacing));
    if (k <= 1) {
        if (chord <= spacing) return;
        k = 2;
    }
    for (int attempt = 0; attempt < 4; ++attempt) {
        samples.resize(k - 1);
        const double du = 1.0 / static_cast<double>(k);
        dvec3 prev = p1;
        double longest = 0.0;
        for (size_t j = 1; j < k; ++j) {
            samples[j - 1] = cubic.eval(static_cast<double>(j) * du);
            longest = std::max(longest, glm::length(samples[j - 1] - prev));
            prev = samples[j - 1];
        }
        longest = std::max(longest, glm::length(p2 - prev));
        if (longest <= spacing) return;
        k = std::max(k + 1, static_cast<size_t>(std::ceil(static_cast<double>(k) * longest / spacing)));
    }
    // Guaranteed: chord <= arc <= max speed * du <= 3 maxLeg / k < spacing.
    k = static_cast<size_t>(std::ceil(3.0 * cubic.maxLeg / spacing)) + 1;
    samples.resize(k - 1);
    for (size_t j = 1; j < k; ++j) samples[j - 1] = cubic.eval(static_cast<double>(j) / static_cast<double>(k));
}

}  // namespace

size_t resampleCurve(const MappedYarns& yarns, size_t c, double spacing, std::vector<dvec3>& outPoints,
                     std::vector<dvec3>* outNormals, ResampleScratch& scratch, ResampleLayout* layout) {
    const bool withNormals = outNormals && !yarns.normals.empty();
    std::vector<dvec3>& pts = scratch.points;
    std::vector<dvec3>& nrm = scratch.normals;
    std::vector<double>& knot = scratch.knots;
    std::vector<dvec3>& samples = scratch.samples;
    const Polylines& in = yarns.curves;
    const bool closed = in.isClosed(c);
    const uint32_t b = in.begin(c), e = in.end(c);
    const double merge2 = (1e-12 * spacing) * (1e-12 * spacing);

    // Step 1: merge consecutive repeated points (and a closed curve's repeated first point).
    pts.clear();
    nrm.clear();
    knot.clear();
    if (layout) {
        layout->kept.clear();
        layout->pieces.clear();
    }
    for (uint32_t i = b; i < e; ++i) {
        if (!pts.empty()) {
            const dvec3 d = in.points[i] - pts.back();
            const double d2 = glm::dot(d, d);
            if (d2 <= merge2) continue;
            knot.push_back(std::sqrt(std::sqrt(d2)));  // centripetal knot interval |d|^(1/2)
        }
        pts.push_back(in.points[i]);
        if (withNormals) nrm.push_back(yarns.normals[i]);
        if (layout) layout->kept.push_back(i - b);
    }
    if (closed) {
        while (pts.size() > 1) {
            const dvec3 d = pts.front() - pts.back();
            const double d2 = glm::dot(d, d);
            if (d2 > merge2) {
                knot.push_back(std::sqrt(std::sqrt(d2)));  // the closing segment
                break;
            }
            pts.pop_back();
            knot.pop_back();
            if (withNormals) nrm.pop_back();
            if (layout) layout->kept.pop_back();
        }
    }
    const size_t n = pts.size();
    const size_t start = outPoints.size();
    if (n < 2) {
        // Degenerate curve: kept as is (0 or 1 point), no segments.
        outPoints.insert(outPoints.end(), pts.begin(), pts.end());
        if (withNormals) outNormals->insert(outNormals->end(), nrm.begin(), nrm.end());
        return n;
    }

    // Step 2: one centripetal Catmull-Rom piece per segment, split so no chord exceeds spacing.
    const size_t segments = closed ? n : n - 1;
    for (size_t s = 0; s < segments; ++s) {
        const size_t s1 = s + 1 == n ? 0 : s + 1;
        const dvec3& p1 = pts[s];
        const dvec3& p2 = pts[s1];
        const double t12 = knot[s];
        outPoints.push_back(p1);
        if (withNormals) outNormals->push_back(nrm[s]);
        const Cubic cubic = segmentCubic(pts.data(), knot.data(), n, closed, s);
        splitPiece(cubic, p1, p2, t12 * t12, spacing, samples);
        if (layout) layout->pieces.push_back(static_cast<uint32_t>(samples.size() + 1));
        if (samples.empty()) continue;
        const size_t k = samples.size() + 1;
        outPoints.insert(outPoints.end(), samples.begin(), samples.end());
        if (withNormals) {
            // Linear in the sample's parameter along the piece, renormalized.
            const double dk = 1.0 / static_cast<double>(k);
            for (size_t j = 1; j < k; ++j)
                outNormals->push_back(lerpNormal(nrm[s], nrm[s1], static_cast<double>(j) * dk));
        }
    }
    if (!closed) {
        outPoints.push_back(pts[n - 1]);
        if (withNormals) outNormals->push_back(nrm[n - 1]);
    }
    return outPoints.size() - start;
}

size_t resampleColours(const glm::vec3* in, bool closed, const ResampleLayout& layout, std::vector<glm::vec3>& out) {
    const size_t n = layout.kept.size(), start = out.size();
    if (n < 2) {
        for (const uint32_t k : layout.kept) out.push_back(in[k]);
        return n;
    }
    for (size_t s = 0; s < layout.pieces.size(); ++s) {
        const glm::vec3 a = in[layout.kept[s]], b = in[layout.kept[s + 1 == n ? 0 : s + 1]];
        const uint32_t k = layout.pieces[s];
        for (uint32_t j = 0; j < k; ++j) out.push_back(2 * j <= k ? a : b);
    }
    if (!closed) out.push_back(in[layout.kept[n - 1]]);
    return out.size() - start;
}

size_t resampleTwist(const float* in, bool closed, const uint32_t* kept, size_t keptCount, const uint32_t* pieces,
                     double* out) {
    if (keptCount < 2) {
        for (size_t i = 0; i < keptCount; ++i) out[i] = in[kept[i]];
        return keptCount;
    }
    size_t o = 0;
    const size_t segments = closed ? keptCount : keptCount - 1;
    for (size_t s = 0; s < segments; ++s) {
        const double a = in[kept[s]], b = in[kept[s + 1 == keptCount ? 0 : s + 1]];
        const uint32_t k = pieces[s];
        out[o++] = a;
        for (uint32_t j = 1; j < k; ++j) out[o++] = a + (b - a) * (double(j) / double(k));
    }
    if (!closed) out[o++] = in[kept[keptCount - 1]];
    return o;
}

size_t resampleCurveWithLayout(const Polylines& curves, size_t c, const uint32_t* kept, size_t keptCount,
                               const uint32_t* pieces, dvec3* out, ResampleScratch& scratch) {
    const bool closed = curves.isClosed(c);
    const dvec3* in = curves.points.data() + curves.begin(c);
    std::vector<dvec3>& pts = scratch.points;
    std::vector<double>& knot = scratch.knots;
    // Step 1: the kept points and their centripetal knot intervals on this pose (coincident
    // points get a tiny interval instead of a division by zero).
    pts.clear();
    knot.clear();
    for (size_t i = 0; i < keptCount; ++i) pts.push_back(in[kept[i]]);
    const size_t n = pts.size();
    if (n < 2) {
        std::copy(pts.begin(), pts.end(), out);
        return n;
    }
    const size_t segments = closed ? n : n - 1;
    // Their reciprocals, each computed once (segmentCubic would divide five times per piece).
    std::vector<double>& inverse = scratch.inverseKnots;
    std::vector<double>& pairInverse = scratch.inversePairs;
    knot.resize(segments);
    inverse.resize(segments);
    pairInverse.resize(segments);
    const bool simd = util::avx2Kernels();
    for (size_t s = knotsWithInverses(pts.data(), n, knot.data(), inverse.data(), simd); s < segments; ++s) {
        knot[s] = knotInterval(pts[s], pts[s + 1 == n ? 0 : s + 1]);
        inverse[s] = 1.0 / knot[s];
    }
    for (size_t s = pairInverses(knot.data(), segments, pairInverse.data(), simd); s < segments; ++s) {
        const size_t next = s + 1 < segments ? s + 1 : (closed ? 0 : s);
        pairInverse[s] = 1.0 / (knot[s] + knot[next]);
    }
    const KnotInverses inv{inverse.data(), pairInverse.data()};
    // Step 2: each piece evaluated at the rest pose's parameters j / k; the interior pieces'
    // coefficients four at a time in AVX2 (fourCubicsAvx2, the same bits).
    size_t o = 0;
    const auto emit = [&](const Cubic& cubic, size_t k) {
        const double du = 1.0 / static_cast<double>(k);
        for (size_t j = 1; j < k; ++j) out[o++] = cubic.eval(static_cast<double>(j) * du);
    };
#if KNIT_HAVE_AVX2_KERNELS
    const size_t groupEnd = simd && n > 5 ? n - 5 : 0;  // groups start below it
#else
    const size_t groupEnd = 0;
#endif
    for (size_t s = 0; s < segments;) {
#if KNIT_HAVE_AVX2_KERNELS
        if (s >= 1 && s < groupEnd) {
            FourCubics four;
            fourCubicsAvx2(pts.data(), knot.data(), inv, s, four);
            for (size_t j = 0; j < 4; ++j, ++s) {
                out[o++] = pts[s];
                if (pieces[s] > 1) emit(Cubic{four.a[j], four.b[j], four.c[j], pts[s]}, pieces[s]);
            }
            continue;
        }
#endif
        out[o++] = pts[s];
        if (pieces[s] > 1)  // fixed pieces: no bounds
            emit(segmentCubic(pts.data(), knot.data(), n, closed, s, false, &inv), pieces[s]);
        ++s;
    }
    if (!closed) out[o++] = pts[n - 1];
    return o;
}

size_t estimateResampledSize(const Polylines& in, size_t c, double spacing) {
    // Each segment becomes ceil(chord / spacing) >= 1 pieces (merged repeated points, chord <=
    // 1e-12 spacing, none); an open curve adds its last point.
    const double inverseSpacing = 1.0 / spacing;
    const uint32_t b = in.begin(c), e = in.end(c);
    auto pieces = [&](const dvec3& p, const dvec3& q) {
        const double k = glm::length(q - p) * inverseSpacing - 1e-9;
        return static_cast<size_t>(std::ceil(std::clamp(k, 0.0, 1e12)));  // clamped: no overflow in the cast
    };
    if (e == b) return 0;
    size_t count = in.isClosed(c) ? 0 : 1;
    for (uint32_t i = b; i + 1 < e; ++i) count += pieces(in.points[i], in.points[i + 1]);
    if (in.isClosed(c) && e > b + 1) count += pieces(in.points[e - 1], in.points[b]);
    return std::max<size_t>(count, 1);
}

namespace {

// Fixed chunks of consecutive curves of about 8192 input points (independent of the thread
// count, so results are deterministic): chunk k is curves [start[k], start[k + 1]).
std::vector<size_t> curveChunks(const Polylines& in) {
    std::vector<size_t> start{0};
    size_t acc = 0;
    for (size_t c = 0; c < in.curveCount(); ++c) {
        acc += in.size(c);
        if (acc >= 8192 && c + 1 < in.curveCount()) {
            start.push_back(c + 1);
            acc = 0;
        }
    }
    start.push_back(in.curveCount());
    return start;
}

// Resampled curves of one chunk, concatenated.
struct CurveBuffer {
    std::vector<dvec3> points;
    std::vector<dvec3> normals;
    std::vector<glm::vec3> colour;
    std::vector<uint32_t> sizes;  // points per curve in this chunk
};

}  // namespace

void validateResampleInput(const MappedYarns& yarns, const ResampleOptions& options) {
    if (!util::positiveFinite(options.spacing))
        throw Error("the ply sample spacing, the ply pitch / the samples per turn, must be a positive finite length, "
                    "got " +
                    std::to_string(options.spacing));
    const Polylines& in = yarns.curves;
    if (!util::validOffsets(in.offsets, in.curveCount(), in.pointCount()))
        throw Error("resampling the yarns: their curve offsets do not match their points");
    const bool withNormals = !yarns.normals.empty();
    if (withNormals && yarns.normals.size() != in.pointCount())
        throw Error("resampling the yarns: " + std::to_string(yarns.normals.size()) + " normals for " +
                    std::to_string(in.pointCount()) + " yarn points");
    if (!yarns.colour.empty() && yarns.colour.size() != in.pointCount())
        throw Error("resampling the yarns: " + std::to_string(yarns.colour.size()) + " colours for " +
                    std::to_string(in.pointCount()) + " yarn points");

    // First non-finite point or normal of each chunk (in parallel), then the first overall.
    const std::vector<size_t> chunkStart = curveChunks(in);
    const size_t chunks = chunkStart.size() - 1;
    std::vector<size_t> firstBad(chunks, SIZE_MAX);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const uint32_t b = in.begin(chunkStart[k]), e = in.begin(chunkStart[k + 1]);
            for (uint32_t i = b; i < e && firstBad[k] == SIZE_MAX; ++i)
                if (!util::finite(in.points[i]) || (withNormals && !util::finite(yarns.normals[i]))) firstBad[k] = i;
        }
    });
    for (size_t k = 0; k < chunks; ++k) {
        if (firstBad[k] == SIZE_MAX) continue;
        const size_t i = firstBad[k];
        const size_t c =
            static_cast<size_t>(std::upper_bound(in.offsets.begin(), in.offsets.end(), i) - in.offsets.begin()) - 1;
        const bool point = !util::finite(in.points[i]);
        throw Error("resampling the yarns: yarn " + std::to_string(c) + (point ? " point " : " normal ") +
                    std::to_string(i - in.begin(c)) + " is not finite");
    }
}

MappedYarns resampleYarns(const MappedYarns& yarns, const ResampleOptions& options) {
    // Step 1: validate options and input first: the loops below never throw.
    validateResampleInput(yarns, options);
    const Polylines& in = yarns.curves;
    const bool withNormals = !yarns.normals.empty(), withColour = !yarns.colour.empty();

    // Step 2: fixed chunks of consecutive curves and a lower bound of their output size.
    const std::vector<size_t> chunkStart = curveChunks(in);
    const size_t chunks = chunkStart.size() - 1;
    std::vector<size_t> estimate(chunks, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k)
            for (size_t c = chunkStart[k]; c < chunkStart[k + 1]; ++c)
                estimate[k] += estimateResampledSize(in, c, options.spacing);
    });
    size_t total = 0;
    for (size_t k = 0; k < chunks; ++k) total += estimate[k];
    if (total > UINT32_MAX)
        throw Error(
            "about " + std::to_string(total) +
            " resampled points (more than 2^32-1) at this spacing; raise the ply pitch or lower the samples per turn");

    // Step 3: resample chunk by chunk into separate buffers.
    std::vector<CurveBuffer> buffers(chunks);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
        ResampleScratch scratch;
        ResampleLayout layout;
        for (size_t k = r.begin(); k < r.end(); ++k) {
            CurveBuffer& buf = buffers[k];
            const size_t reserve = 16 + estimate[k] + estimate[k] / 4;  // curved pieces need a few more
            buf.points.reserve(reserve);
            if (withNormals) buf.normals.reserve(reserve);
            for (size_t c = chunkStart[k]; c < chunkStart[k + 1]; ++c) {
                buf.sizes.push_back(static_cast<uint32_t>(resampleCurve(yarns, c, options.spacing, buf.points,
                                                                        withNormals ? &buf.normals : nullptr, scratch,
                                                                        withColour ? &layout : nullptr)));
                if (withColour) resampleColours(yarns.colour.data() + in.begin(c), in.isClosed(c), layout, buf.colour);
            }
        }
    });

    // Step 4: concatenate the chunks in curve order.
    MappedYarns out;
    std::vector<size_t> pointStart(chunks + 1, 0);
    out.curves.offsets.reserve(in.curveCount() + 1);
    out.curves.closed.assign(in.closed.begin(), in.closed.end());
    for (size_t k = 0; k < chunks; ++k) pointStart[k + 1] = pointStart[k] + buffers[k].points.size();
    if (pointStart[chunks] > UINT32_MAX)
        throw Error(
            "more than 2^32-1 resampled points at this spacing; raise the ply pitch or lower the samples per turn");
    for (size_t k = 0; k < chunks; ++k)
        for (const uint32_t size : buffers[k].sizes) out.curves.offsets.push_back(out.curves.offsets.back() + size);
    // The two big arrays are allocated (and zero-filled) concurrently.
    tbb::parallel_invoke([&] { out.curves.points.resize(pointStart[chunks]); },
                         [&] {
                             if (withNormals) out.normals.resize(pointStart[chunks]);
                         },
                         [&] { out.colour.resize(withColour ? pointStart[chunks] : 0); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            std::copy(buffers[k].points.begin(), buffers[k].points.end(), out.curves.points.begin() + pointStart[k]);
            if (withNormals)
                std::copy(buffers[k].normals.begin(), buffers[k].normals.end(), out.normals.begin() + pointStart[k]);
            if (withColour)
                std::copy(buffers[k].colour.begin(), buffers[k].colour.end(), out.colour.begin() + pointStart[k]);
            std::vector<dvec3>().swap(buffers[k].points);  // release memory early
            std::vector<dvec3>().swap(buffers[k].normals);
            std::vector<glm::vec3>().swap(buffers[k].colour);
        }
    });
    return out;
}

}  // namespace knit
