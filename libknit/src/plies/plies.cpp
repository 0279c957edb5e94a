// plies.cpp — plies twisted around the mapped yarn centrelines.
//
// Steps (PlyGenerator::generate, per yarn; makePlies runs it over fixed yarn batches in
// parallel and concatenates): resample the yarn (spacing = pitch / samplesPerTurn);
// rotation-minimizing frames seeded with the surface normal (curveFrames, same result as
// rotationMinimizingFrames); sweep the helices (the two steps are impl::PlyKernel,
// plies_kernel.hpp)
//   c_i(s) = C(s) + R_ply (cos(theta(s) + 2 pi i / n) N(s) + sin(theta(s) + 2 pi i / n) B(s)),
// with B = T x N and s the arc length of the resampled polyline from the yarn's first point.
//
// Twist convention. Hold the yarn vertical. In an S twist the strands on the near side slant
// like the middle stroke of the letter "S" (upper left to lower right, "\"); in a Z twist like
// the middle of "Z" ("/"). A Z strand is a right-handed helix (a standard screw thread): moving
// along T it turns counter-clockwise about T, i.e. from N toward B = T x N, so
//   Z: theta = +2 pi s / pitch,   S: theta = -2 pi s / pitch   (S is left-handed).
// Handedness is intrinsic (independent of the direction the yarn is traversed). For a helix
// around a straight yarn, dot(T, cross(radial, dc/ds)) = R_ply * dtheta/ds, positive for Z and
// negative for S; equivalently the torsion of a Z ply is positive.
//
// Closed yarns: the number of turns L / pitch is rounded to the nearest integer >= 1 and the
// pitch becomes L / turns, so theta(L) is a multiple of 2 pi and the (closed) ply curves close
// with no twist jump; the frames are closed by rotationMinimizingFrames.
//
// Degenerate yarns (fewer than 2 distinct points after resampling) produce no ply curves; use
// yarnOfCurve to map ply curves back to yarns.
//
// n = 1: with the automatic radii the single ply is the yarn itself: centre radius 0 (on the
// centreline), ply radius = yarn radius; `radial` then still holds the unit phase direction
// cos(theta) N + sin(theta) B.
#include "knit/plies.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "frames_curve.hpp"
#include "helices_simd.hpp"
#include "knit/error.hpp"
#include "plies_kernel.hpp"
#include "resample_curve.hpp"
#include "util/checks.hpp"
#include "util/csr.hpp"
#include "util/math.hpp"
#include "util/simd.hpp"

namespace knit {
namespace {

using glm::dvec3;

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// `setting` names the value in words (knit/setting_spelling.hpp).
void requireNonNegativeFinite(double v, const char* setting, const char* meaning) {
    if (!std::isfinite(v) || v < 0.0)
        throw Error(std::string(setting) + " must be a finite length >= 0 in metres (" + meaning + "), got " + num(v));
}

}  // namespace

PlyOptions resolvePlyOptions(const PlyOptions& options) {
    PlyOptions o = options;
    // Validate.
    if (o.count < 1 || o.count > 16)
        throw Error("the number of plies must be in 1..16, got " + std::to_string(o.count));
    if (!util::positiveFinite(o.yarnRadius))
        throw Error("the yarn radius " + num(o.yarnRadius) +
                    " m must be a positive finite length; it is the pattern's radius times its placement scale: "
                    "check the pattern file's radius and the repeats");
    requireNonNegativeFinite(o.centerRadius, "the ply centre radius", "0 = touching plies filling the yarn");
    requireNonNegativeFinite(o.plyRadius, "the ply radius", "0 = touching plies filling the yarn");
    requireNonNegativeFinite(o.pitch, "the ply pitch", "0 = 6 yarn radii");
    if (o.samplesPerTurn < 3 || o.samplesPerTurn > 1024)
        throw Error("the samples per turn must be in 3..1024, got " + std::to_string(o.samplesPerTurn));
    if (o.twist != Twist::S && o.twist != Twist::Z)
        throw Error("the twist direction must be S or Z, got " + std::to_string(static_cast<int>(o.twist)));
    // Fill defaults: touching plies that fill the yarn.
    const double n = static_cast<double>(o.count);
    const double sinPiN = o.count == 1 ? 0.0 : std::sin(util::kPi / n);
    if (o.centerRadius == 0.0 && o.count > 1) o.centerRadius = o.yarnRadius / (1.0 + sinPiN);
    if (o.plyRadius == 0.0) {
        o.plyRadius = o.count == 1 ? o.yarnRadius - o.centerRadius : o.centerRadius * sinPiN;
        if (!(o.plyRadius > 0.0))
            throw Error("the ply radius: cannot derive it for one ply with the ply centre radius " +
                        num(o.centerRadius) + " >= the yarn radius " + num(o.yarnRadius) +
                        "; set the ply radius explicitly");
    }
    if (o.pitch == 0.0) o.pitch = 6.0 * o.yarnRadius;
    return o;
}

PlyGenerator::PlyGenerator(const MappedYarns& yarns, const PlyOptions& options, TopologyOnly)
    : yarns_(yarns), options_(resolvePlyOptions(options)) {
    spacing_ = options_.pitch / static_cast<double>(options_.samplesPerTurn);
    for (int i = 0; i < options_.count; ++i) {
        cosPly_[i] = std::cos(util::kTwoPi * i / options_.count);
        sinPly_[i] = std::sin(util::kTwoPi * i / options_.count);
    }
}

PlyGenerator::PlyGenerator(const MappedYarns& yarns, const PlyOptions& options)
    : PlyGenerator(yarns, options, TopologyOnly{}) {
    ResampleOptions ro;
    ro.spacing = spacing_;
    validateResampleInput(yarns_, ro);
    if (!yarns_.twist.empty() && yarns_.twist.size() != yarns_.curves.points.size())
        throw Error("the yarns have " + std::to_string(yarns_.twist.size()) + " twist values for " +
                    std::to_string(yarns_.curves.points.size()) + " points");
}

size_t PlyGenerator::estimatePoints(size_t y) const {
    const size_t samples = estimateResampledSize(yarns_.curves, y, spacing_);
    return samples < 2 ? 0 : static_cast<size_t>(options_.count) * samples;  // < 2 points: no plies
}

PlyScratch::PlyScratch() = default;
PlyScratch::~PlyScratch() = default;
PlyScratch::PlyScratch(PlyScratch&&) noexcept = default;
PlyScratch& PlyScratch::operator=(PlyScratch&&) noexcept = default;

namespace impl {

PlyGenerator PlyKernel::replayGenerator(const MappedYarns& topology, const PlyOptions& options) {
    const std::vector<uint32_t>& o = topology.curves.offsets;
    if (o.empty() || !util::validOffsets(o, topology.curves.curveCount(), o.back()))
        throw Error("replaying the plies: the yarn offsets decrease");
    return PlyGenerator(topology, options, PlyGenerator::TopologyOnly{});
}

PlyScratch::Buffers& PlyKernel::buffers(PlyScratch& scratch) {
    if (!scratch.buffers_) scratch.buffers_ = std::make_unique<PlyScratch::Buffers>();
    return *scratch.buffers_;
}

size_t PlyKernel::centreline(const PlyGenerator& g, size_t y, std::vector<dvec3>& centre, PlyScratch& scratch,
                             std::vector<glm::vec3>* colour, std::vector<double>* twist, ResampleLayout* layout) {
    PlyScratch::Buffers& buf = buffers(scratch);
    const std::vector<glm::vec3>& in = g.yarns_.colour;
    const bool withColour = colour && !in.empty(), withTwist = twist && !g.yarns_.twist.empty();
    ResampleLayout* record = layout ? layout : withColour || withTwist ? &buf.layout : nullptr;
    const size_t m = resampleCurve(g.yarns_, y, g.spacing_, centre, nullptr, buf.resample, record);
    if (withColour)
        resampleColours(in.data() + g.yarns_.curves.begin(y), g.yarns_.curves.isClosed(y), *record, *colour);
    if (withTwist) {
        const size_t start = twist->size();
        twist->resize(start + m);
        resampleTwist(g.yarns_.twist.data() + g.yarns_.curves.begin(y), g.yarns_.curves.isClosed(y),
                      record->kept.data(), record->kept.size(), record->pieces.data(), twist->data() + start);
    }
    return m;
}

void PlyKernel::plyColours(const glm::vec3* colour, size_t m, uint32_t count, glm::vec3* out) {
    for (uint32_t i = 0; i < count; ++i) std::copy(colour, colour + m, out + i * m);
}

double PlyKernel::arcAndPitch(const PlyGenerator& g, size_t y, const dvec3* X, size_t m, std::vector<double>& arc) {
    arc.resize(m);
    arc[0] = 0.0;
    for (size_t j = 1; j < m; ++j) arc[j] = arc[j - 1] + glm::length(X[j] - X[j - 1]);
    if (!g.yarns_.curves.isClosed(y)) return g.options_.pitch;
    const double length = arc[m - 1] + glm::length(X[0] - X[m - 1]);
    const double turns = std::max(1.0, std::round(length / g.options_.pitch));
    return length / turns;
}

void PlyKernel::sweep(const PlyGenerator& g, size_t y, const dvec3* X, size_t m, dvec3* P, dvec3* D,
                      PlyScratch& scratch, const double* twist) {
    // Arc length; closed yarns get an integer number of turns so the helix closes.
    PlyScratch::Buffers& buf = buffers(scratch);
    const double pitch = arcAndPitch(g, y, X, m, buf.arc);
    // The frame seed is the surface normal at the first point, which resampling keeps unchanged
    // (no normals need interpolating).
    const dvec3* seed = g.yarns_.normals.empty() ? nullptr : g.yarns_.normals.data() + g.yarns_.curves.begin(y);
    sweepWithPhase(g, y, X, m, buf.arc.data(), pitch, seed, P, D, scratch, twist);
}

namespace {

// Step 2 of a sweep: the helices around the framed centreline, with phase offsets 2 pi i / n;
// `phase(j)` gives (cos theta, sin theta) of point j.
template <class Phase>
void helices(const PlyOptions& opt, const dvec3* X, const dvec3* T, const dvec3* N, size_t m, const double* cosPly,
             const double* sinPly, Phase phase, dvec3* P, dvec3* D, size_t first = 0) {
    const uint32_t n = static_cast<uint32_t>(opt.count);
    const double R = opt.centerRadius;
    for (size_t j = first; j < m; ++j) {
        const glm::dvec2 cs = phase(j);
        const double ct = cs.x, st = cs.y;
        const dvec3 nj = N[j];
        const dvec3 bj = glm::cross(T[j], nj);
        const dvec3 xj = X[j];
        for (uint32_t i = 0; i < n; ++i) {
            const double c = ct * cosPly[i] - st * sinPly[i];  // cos(theta + 2 pi i / n)
            const double s = st * cosPly[i] + ct * sinPly[i];  // sin(theta + 2 pi i / n)
            const dvec3 radial = c * nj + s * bj;
            P[i * m + j] = xj + R * radial;
            if (D) D[i * m + j] = radial;
        }
    }
}

}  // namespace

void PlyKernel::frames(const PlyGenerator& g, size_t y, const dvec3* X, size_t m, const dvec3* seed,
                       const dvec3* seedTangent, PlyScratch::Buffers& buf, FramePrecision precision) {
    buf.tangent.resize(m);
    buf.normal.resize(m);
    FrameOptions options;
    options.precision = precision;
    if (precision == FramePrecision::Float32) buf.frameFloats.resize(6 * m);
    curveFrames(X, m, g.yarns_.curves.isClosed(y), seed, buf.tangent.data(), buf.normal.data(), options, seedTangent,
                precision == FramePrecision::Float32 ? buf.frameFloats.data() : nullptr);
}

double PlyKernel::twistRate(const PlyGenerator& g, double pitch) {
    return (g.options_.twist == Twist::Z ? 1.0 : -1.0) * util::kTwoPi / pitch;  // dtheta/ds
}

void PlyKernel::sweepWithPhase(const PlyGenerator& g, size_t y, const dvec3* X, size_t m, const double* arc,
                               double pitch, const dvec3* seed, dvec3* P, dvec3* D, PlyScratch& scratch,
                               const double* twist) {
    // Step 1: rotation-minimizing frames; step 2: the helices.
    PlyScratch::Buffers& buf = buffers(scratch);
    frames(g, y, X, m, seed, nullptr, buf);
    const double rate = twistRate(g, pitch);
    helices(
        g.options_, X, buf.tangent.data(), buf.normal.data(), m, g.cosPly_, g.sinPly_,
        [&](size_t j) {
            const double theta = twist ? rate * arc[j] + twist[j] : rate * arc[j];  // strain tables' twist
            return glm::dvec2(std::cos(theta), std::sin(theta));
        },
        P, D);
}

void PlyKernel::sweepWithCosSin(const PlyGenerator& g, size_t y, const dvec3* X, size_t m, const glm::dvec2* phase,
                                const dvec3* seed, const dvec3* seedTangent, dvec3* P, PlyScratch& scratch,
                                dvec3* radial, FramePrecision precision) {
    PlyScratch::Buffers& buf = buffers(scratch);
    frames(g, y, X, m, seed, seedTangent, buf, precision);
    // Four points at a time in AVX2 (helices_simd.cpp, bit for bit), the rest here.
    const HelixInput in{
        X,         buf.tangent.data(), buf.normal.data(),      phase, m, static_cast<uint32_t>(g.options_.count),
        g.cosPly_, g.sinPly_,          g.options_.centerRadius};
    const size_t done = helicesCosSin(in, P, radial, util::avx2Kernels());
    helices(
        g.options_, X, buf.tangent.data(), buf.normal.data(), m, g.cosPly_, g.sinPly_,
        [&](size_t j) { return phase[j]; }, P, radial, done);
}

}  // namespace impl

void PlyGenerator::generate(size_t first, size_t last, Plies& out, PlyScratch& scratch, bool withRadial) const {
    const uint32_t n = static_cast<uint32_t>(options_.count);
    // Step 1: empty the batch (capacity is kept for the next one).
    out.curves.points.clear();
    out.curves.offsets.assign(1, 0);
    out.curves.closed.clear();
    out.yarnOfCurve.clear();
    out.plyOfCurve.clear();
    out.radial.clear();
    out.colour.clear();
    out.plyRadius = options_.plyRadius;
    out.centerRadius = options_.centerRadius;
    out.pitch = options_.pitch;

    std::vector<dvec3>& centre = impl::PlyKernel::buffers(scratch).centre;
    std::vector<glm::vec3>& colour = impl::PlyKernel::buffers(scratch).colour;
    std::vector<double>& twist = impl::PlyKernel::buffers(scratch).twist;
    for (size_t y = first; y < last; ++y) {
        // Step 2: resample the centreline (and its colours).
        centre.clear();
        colour.clear();
        twist.clear();
        const size_t m = impl::PlyKernel::centreline(*this, y, centre, scratch, &colour, &twist);
        if (m < 2) continue;  // degenerate yarn: no plies
        // Step 3: n curves of m points (yarn-major, ply-minor) swept around it.
        const size_t base = out.curves.points.size();
        out.curves.points.resize(base + n * m);
        if (withRadial) out.radial.resize(base + n * m);
        for (uint32_t i = 0; i < n; ++i) {
            out.curves.offsets.push_back(static_cast<uint32_t>(base + (i + 1) * m));
            out.curves.closed.push_back(yarns_.curves.closed[y]);
            out.yarnOfCurve.push_back(static_cast<uint32_t>(y));
            out.plyOfCurve.push_back(static_cast<uint8_t>(i));
        }
        impl::PlyKernel::sweep(*this, y, centre.data(), m, out.curves.points.data() + base,
                               withRadial ? out.radial.data() + base : nullptr, scratch,
                               twist.empty() ? nullptr : twist.data());
        if (!colour.empty()) {
            out.colour.resize(base + n * m);
            impl::PlyKernel::plyColours(colour.data(), m, n, out.colour.data() + base);
        }
    }
}

Plies makePlies(const MappedYarns& yarns, const PlyOptions& options) {
    // Resolve and validate (options and yarns); nothing after this throws a knit::Error except
    // the size limit.
    return makePlies(PlyGenerator(yarns, options));
}

Plies makePlies(const PlyGenerator& generator) {
    const Polylines& C = generator.yarns().curves;

    // Step 1: fixed batches of consecutive yarns (about 8192 input points each: independent of
    // the thread count, so the result is deterministic) and the size limit on their estimate.
    std::vector<size_t> batchStart{0};
    size_t estimate = 0, acc = 0;
    for (size_t y = 0; y < C.curveCount(); ++y) {
        estimate += generator.estimatePoints(y);
        acc += C.size(y);
        if (acc >= 8192 && y + 1 < C.curveCount()) {
            batchStart.push_back(y + 1);
            acc = 0;
        }
    }
    batchStart.push_back(C.curveCount());
    const auto tooMany = [] {
        return Error("more than 2^32-1 ply points; raise the ply pitch or lower the samples per turn");
    };
    if (estimate > UINT32_MAX) throw tooMany();

    // Step 2: resample the centrelines batch by batch, in parallel (their sizes fix the layout).
    const size_t batches = batchStart.size() - 1;
    std::vector<std::vector<dvec3>> centres(batches);
    std::vector<std::vector<glm::vec3>> colours(batches);  // empty without colours
    std::vector<std::vector<double>> twists(batches);      // empty without twist
    std::vector<size_t> samples(C.curveCount(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches, 1), [&](const tbb::blocked_range<size_t>& r) {
        PlyScratch scratch;
        for (size_t k = r.begin(); k < r.end(); ++k)
            for (size_t y = batchStart[k]; y < batchStart[k + 1]; ++y)
                samples[y] = impl::PlyKernel::centreline(generator, y, centres[k], scratch, &colours[k], &twists[k]);
    });

    // Step 3: layout, yarn-major and ply-minor (yarns with < 2 samples get no plies).
    const uint32_t n = static_cast<uint32_t>(generator.options().count);
    Plies out;
    out.plyRadius = generator.options().plyRadius;
    out.centerRadius = generator.options().centerRadius;
    out.pitch = generator.options().pitch;
    std::vector<size_t> firstPoint(C.curveCount(), 0);
    size_t total = 0;
    for (size_t y = 0; y < C.curveCount(); ++y) {
        firstPoint[y] = total;
        if (samples[y] < 2) continue;
        for (uint32_t i = 0; i < n; ++i) {
            total += samples[y];
            if (total > UINT32_MAX) throw tooMany();
            out.curves.offsets.push_back(static_cast<uint32_t>(total));
            out.curves.closed.push_back(C.closed[y]);
            out.yarnOfCurve.push_back(static_cast<uint32_t>(y));
            out.plyOfCurve.push_back(static_cast<uint8_t>(i));
        }
    }

    // Step 4: sweep every yarn's plies straight into place, in parallel.
    const bool withColour = !generator.yarns().colour.empty();
    tbb::parallel_invoke([&] { out.curves.points.resize(total); }, [&] { out.radial.resize(total); },
                         [&] { out.colour.resize(withColour ? total : 0); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches, 1), [&](const tbb::blocked_range<size_t>& r) {
        PlyScratch scratch;
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const dvec3* X = centres[k].data();
            const glm::vec3* colour = colours[k].data();
            const double* twist = twists[k].empty() ? nullptr : twists[k].data();
            for (size_t y = batchStart[k]; y < batchStart[k + 1]; ++y) {
                const size_t m = samples[y];
                if (m >= 2) {
                    impl::PlyKernel::sweep(generator, y, X, m, out.curves.points.data() + firstPoint[y],
                                           out.radial.data() + firstPoint[y], scratch, twist);
                    if (withColour) impl::PlyKernel::plyColours(colour, m, n, out.colour.data() + firstPoint[y]);
                }
                X += m;
                if (withColour) colour += m;
                if (twist) twist += m;
            }
            std::vector<dvec3>().swap(centres[k]);  // release memory early
            std::vector<glm::vec3>().swap(colours[k]);
            std::vector<double>().swap(twists[k]);
        }
    });
    return out;
}

}  // namespace knit
