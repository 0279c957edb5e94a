// The plies' AVX2 kernels (frames_transport.cpp, helices_simd.cpp) against their scalar
// definitions, and the one-matrix transport of curveFrames against two reflections one after the
// other. On a CPU without AVX2 the `simd` calls do nothing and the comparisons are trivial.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "plies/frames_curve.hpp"
#include "plies/frames_transport.hpp"
#include "plies/helices_simd.hpp"
#include "util/simd.hpp"

namespace knit {
namespace {

using glm::dvec3;

template <class T>
bool sameBytes(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// A wavy helix of n points with a repeated point, an exact reversal and a straight run.
std::vector<dvec3> testCurve(size_t n) {
    std::vector<dvec3> p;
    for (size_t i = 0; i < n; ++i) {
        const double s = 0.05 * double(i);
        p.emplace_back(0.002 * std::cos(s), 0.002 * std::sin(s) + 1e-4 * std::sin(7.3 * s), 3e-4 * s);
    }
    p[40] = p[39];  // zero-length segment
    p[81] = p[79];  // back onto an earlier point: a reversal
    for (size_t i = 120; i < 140; ++i) p[i] = p[119] + dvec3(0.0, 0.0, 1e-4 * double(i - 119));  // straight
    return p;
}

TEST(FramesSimd, kernelsAreTheScalarDefinitionsBitForBit) {
    if (!util::avx2Kernels()) GTEST_SKIP() << "no AVX2 on this CPU (or KNIT_SIMD=0): only the scalar code runs";
    const std::vector<dvec3> x = testCurve(301);
    std::vector<dvec3> T(x.size()), N(x.size());
    curveFrames(x.data(), x.size(), false, nullptr, T.data(), N.data());

    // The transport coefficients: AVX2 and scalar, every count and offset.
    for (size_t first : {0, 1, 38, 77, 117}) {
        for (size_t count : {1, 3, 4, 7, 64}) {
            impl::TransportBlock a{}, b{};
            impl::transportCoefficients(x.data(), T.data(), first, count, a, true);
            impl::transportCoefficients(x.data(), T.data(), first, count, b, false);
            for (size_t k = 0; k < count; ++k) {
                EXPECT_EQ(a.reversal[k], b.reversal[k]) << first + k;
                for (int e = 0; e < 9; ++e) EXPECT_TRUE(sameBytes(a.m[e][k], b.m[e][k])) << first + k << " " << e;
            }
        }
    }
    // Step 1: v / |v| up to the group holding the zero-length segment 39 -> 40.
    std::vector<dvec3> dT(x.size(), dvec3(7.0)), dN(x.size(), dvec3(7.0));
    const size_t done = impl::unitDirections(x.data(), x.size(), dT.data(), dN.data(), true);
    EXPECT_EQ(done, 36u);
    EXPECT_EQ(impl::unitDirections(x.data(), x.size(), dT.data(), dN.data(), false), 0u);
    for (size_t k = 0; k < done; ++k) {
        const dvec3 v = x[k + 1] - x[k];
        const dvec3 d = v / glm::length(v);
        EXPECT_TRUE(sameBytes(dT[k], d) && sameBytes(dN[k], d)) << k;
    }
    EXPECT_TRUE(sameBytes(dT[done], dvec3(7.0)));
    // Step 2: normalized sums of the directions on either side, in place.
    std::vector<dvec3> dirs(x.size() - 1);
    for (size_t k = 0; k + 1 < x.size(); ++k) dirs[k] = glm::normalize(x[k + 1] - x[k] + dvec3(0.0, 1e-3, 0.0));
    dirs[60] = -dirs[59];  // a hairpin: the sum vanishes, the outgoing direction stays
    std::vector<dvec3> t = dirs;
    const size_t tangents = impl::pointTangents(dirs.data(), t.data(), 1, dirs.size(), true);
    EXPECT_EQ(tangents, 1 + (dirs.size() - 1) / 4 * 4);
    for (size_t i = 1; i < tangents; ++i) {
        const dvec3 sum = dirs[i - 1] + dirs[i];
        const double len = glm::length(sum);
        EXPECT_TRUE(sameBytes(t[i], len > 1e-6 ? sum / len : dirs[i])) << i;
    }
    // The helices: ply i's point j = X + R (c N + s (T x N)).
    const double cosPly[3] = {1.0, std::cos(2.0944), std::cos(4.18879)};
    const double sinPly[3] = {0.0, std::sin(2.0944), std::sin(4.18879)};
    std::vector<glm::dvec2> phase(x.size());
    for (size_t j = 0; j < x.size(); ++j) phase[j] = {std::cos(0.3 * double(j)), std::sin(0.3 * double(j))};
    const size_t m = x.size();
    std::vector<dvec3> P(3 * m, dvec3(7.0)), D(3 * m, dvec3(7.0));
    const impl::HelixInput in{x.data(), T.data(), N.data(), phase.data(), m, 3, cosPly, sinPly, 2.5e-4};
    const size_t helix = impl::helicesCosSin(in, P.data(), D.data(), true);
    EXPECT_EQ(helix, m / 4 * 4);
    for (uint32_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < m; ++j) {
            const double c = phase[j].x * cosPly[i] - phase[j].y * sinPly[i];
            const double s = phase[j].y * cosPly[i] + phase[j].x * sinPly[i];
            const dvec3 radial = c * N[j] + s * glm::cross(T[j], N[j]);
            const bool mine = j < helix;
            EXPECT_TRUE(sameBytes(P[i * m + j], mine ? x[j] + 2.5e-4 * radial : dvec3(7.0))) << i << " " << j;
            EXPECT_TRUE(sameBytes(D[i * m + j], mine ? radial : dvec3(7.0))) << i << " " << j;
        }
}

// curveFrames fills the next block's matrices a few slots at a time during the chain: slots
// [begin, count), filled four at a time or from an odd slot, are those of one call for the
// whole block, and the slots outside them are left as they were.
TEST(FramesSimd, transportCoefficientsFromASlotAreTheWholeBlocks) {
    const std::vector<dvec3> x = testCurve(301);
    std::vector<dvec3> T(x.size()), N(x.size());
    curveFrames(x.data(), x.size(), false, nullptr, T.data(), N.data());
    for (bool simd : {util::avx2Kernels(), false}) {
        for (size_t first : {0, 38, 77}) {
            impl::TransportBlock whole{}, parts{};
            impl::transportCoefficients(x.data(), T.data(), first, 64, whole, simd);
            for (int e = 0; e < 9; ++e) std::fill(parts.m[e], parts.m[e] + 64, 7.0);
            for (size_t k = 0; k < 64; k += 4)
                impl::transportCoefficients(x.data(), T.data(), first, std::min<size_t>(k + 4, 62), parts, simd, k);
            impl::TransportBlock late{};  // one call from slot 9: the slots before it untouched
            for (int e = 0; e < 9; ++e) std::fill(late.m[e], late.m[e] + 64, 7.0);
            impl::transportCoefficients(x.data(), T.data(), first, 30, late, simd, 9);
            for (size_t k = 0; k < 30; ++k)
                for (int e = 0; e < 9; ++e)
                    EXPECT_TRUE(k < 9 ? late.m[e][k] == 7.0 : sameBytes(whole.m[e][k], late.m[e][k])) << first + k;
            for (size_t k = 0; k < 64; ++k) {
                if (k < 62) EXPECT_EQ(whole.reversal[k], parts.reversal[k]) << first + k;
                for (int e = 0; e < 9; ++e)
                    EXPECT_TRUE(k < 62 ? sameBytes(whole.m[e][k], parts.m[e][k]) : parts.m[e][k] == 7.0)
                        << simd << " " << first + k << " " << e;
            }
        }
    }
}

// The transport's two reflections multiplied into one matrix (rounded differently) stay within
// 1e-13 (measured: 8e-15) of the two reflections applied one after the other, over 20,000 steps (the
// renormalization every 16 steps keeps the difference from growing).
TEST(FramesSimd, oneMatrixTransportIsTwoReflectionsToRounding) {
    const size_t n = 20000;
    std::vector<dvec3> x(n);
    for (size_t i = 0; i < n; ++i) {
        const double s = 0.05 * double(i);
        x[i] = dvec3(0.002 * std::cos(s), 0.002 * std::sin(s) + 1e-4 * std::sin(7.3 * s), 3e-4 * s);
    }
    const dvec3 seed(0.3, 0.1, 1.0);
    std::vector<dvec3> T(n), N(n);
    curveFrames(x.data(), n, false, &seed, T.data(), N.data());
    // The reference: the same tangents and first normal, then per step two reflections, and the
    // projection and normalization on the same steps as curveFrames.
    dvec3 r = N[0];
    double worst = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) {
        const dvec3 v1 = x[i + 1] - x[i];
        const double a1 = 2.0 / glm::dot(v1, v1);
        const dvec3 rL = r - (a1 * glm::dot(v1, r)) * v1;
        const dvec3 v2 = T[i + 1] - (T[i] - (a1 * glm::dot(v1, T[i])) * v1);
        const double c2 = glm::dot(v2, v2);
        r = c2 > 1e-24 ? rL - ((2.0 / c2) * glm::dot(v2, rL)) * v2 : rL;
        if ((i & 15u) == 15u || i + 2 == n) r = glm::normalize(r - glm::dot(r, T[i + 1]) * T[i + 1]);
        worst = std::max(worst, glm::length(N[i + 1] - r));
    }
    EXPECT_LT(worst, 1e-13);
    RecordProperty("maxNormalDifference", std::to_string(worst));
    std::printf("largest difference of a unit normal from two reflections: %.3g\n", worst);
}

// The largest distance between unit normals of the float32 transport and the double one.
double floatNormalDrift(const std::vector<dvec3>& x) {
    const size_t n = x.size();
    const dvec3 seed(0.3, 0.1, 1.0);
    std::vector<dvec3> T(n), N(n), Tf(n), Nf(n);
    FrameOptions o;
    curveFrames(x.data(), n, false, &seed, T.data(), N.data(), o);
    o.precision = FramePrecision::Float32;
    curveFrames(x.data(), n, false, &seed, Tf.data(), Nf.data(), o);
    double worst = 0.0;
    for (size_t i = 0; i < n; ++i) worst = std::max(worst, glm::length(N[i] - Nf[i]));
    return worst;
}

TEST(FramesSimd, floatTransportAlongLongYarnsStaysNearTheDoubleOne) {
    const size_t n = 200000;
    std::vector<dvec3> wavy(n), straight(n), tight(n);
    for (size_t i = 0; i < n; ++i) {
        const double s = 0.05 * double(i);
        wavy[i] = dvec3(0.002 * std::cos(s), 0.002 * std::sin(s) + 1e-4 * std::sin(7.3 * s), 3e-4 * s);
        straight[i] = dvec3(0.4 + 1e-4 * double(i), 0.3 + 1e-9 * std::sin(0.01 * double(i)), 0.2);
        const double u = 0.7 * double(i);
        tight[i] = dvec3(0.3 + 1e-4 * std::cos(u), 0.3 + 1e-4 * std::sin(u), 1e-6 * double(i));
    }
    const double w = floatNormalDrift(wavy), st = floatNormalDrift(straight), ti = floatNormalDrift(tight);
    std::printf("float transport normal drift: wavy %.3g straight %.3g tight %.3g\n", w, st, ti);
    EXPECT_LT(std::max(w, std::max(st, ti)), 1e-4);
}

}  // namespace
}  // namespace knit
