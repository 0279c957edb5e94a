// plies.cpp — plies twisted around the mapped yarn centrelines.
//
// Steps: resolve/validate options; resample each yarn (spacing = pitch / samplesPerTurn);
// rotation-minimizing frames seeded with the surface normal (curveFrames per yarn, same
// result as rotationMinimizingFrames); sweep the helices
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

#include "knit/error.hpp"
#include "knit/resample.hpp"

namespace knit {
namespace {

using glm::dvec3;
constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

void requireNonNegativeFinite(double v, const char* name, const char* meaning) {
    if (!std::isfinite(v) || v < 0.0)
        throw Error(std::string("PlyOptions.") + name + " must be a finite value >= 0 (" + meaning + "), got " + num(v));
}

}  // namespace

PlyOptions resolvePlyOptions(const PlyOptions& options) {
    PlyOptions o = options;
    // Validate.
    if (o.count < 1 || o.count > 16)
        throw Error("PlyOptions.count must be in 1..16, got " + std::to_string(o.count));
    if (!std::isfinite(o.yarnRadius) || !(o.yarnRadius > 0.0))
        throw Error("PlyOptions.yarnRadius must be a positive finite length, got " + num(o.yarnRadius));
    requireNonNegativeFinite(o.centerRadius, "centerRadius", "0 = touching plies filling the yarn");
    requireNonNegativeFinite(o.plyRadius, "plyRadius", "0 = touching plies filling the yarn");
    requireNonNegativeFinite(o.pitch, "pitch", "0 = 6 yarn radii");
    if (o.samplesPerTurn < 3 || o.samplesPerTurn > 1024)
        throw Error("PlyOptions.samplesPerTurn must be in 3..1024, got " + std::to_string(o.samplesPerTurn));
    if (o.twist != Twist::S && o.twist != Twist::Z)
        throw Error("PlyOptions.twist must be Twist::S or Twist::Z, got " +
                    std::to_string(static_cast<int>(o.twist)));
    // Fill defaults: touching plies that fill the yarn.
    const double n = static_cast<double>(o.count);
    const double sinPiN = o.count == 1 ? 0.0 : std::sin(kPi / n);
    if (o.centerRadius == 0.0 && o.count > 1) o.centerRadius = o.yarnRadius / (1.0 + sinPiN);
    if (o.plyRadius == 0.0) {
        o.plyRadius = o.count == 1 ? o.yarnRadius - o.centerRadius : o.centerRadius * sinPiN;
        if (!(o.plyRadius > 0.0))
            throw Error("PlyOptions.plyRadius: cannot derive it for one ply with centerRadius " + num(o.centerRadius) +
                        " >= yarnRadius " + num(o.yarnRadius) + "; set plyRadius explicitly");
    }
    if (o.pitch == 0.0) o.pitch = 6.0 * o.yarnRadius;
    return o;
}

Plies makePlies(const MappedYarns& yarns, const PlyOptions& options) {
    const PlyOptions opt = resolvePlyOptions(options);

    // Step 1: resample (validates the yarns).
    ResampleOptions ro;
    ro.spacing = opt.pitch / static_cast<double>(opt.samplesPerTurn);
    const MappedYarns rs = resampleYarns(yarns, ro);
    const Polylines& C = rs.curves;
    const bool haveSeeds = !rs.normals.empty();

    // Step 2: output layout, yarn-major and ply-minor.
    const size_t yarnCount = C.curveCount();
    const uint32_t n = static_cast<uint32_t>(opt.count);
    std::vector<size_t> firstCurve(yarnCount + 1, 0);
    size_t totalPoints = 0;
    for (size_t y = 0; y < yarnCount; ++y) {
        const size_t plies = C.size(y) >= 2 ? n : 0;
        firstCurve[y + 1] = firstCurve[y] + plies;
        totalPoints += plies * C.size(y);
    }
    if (totalPoints > UINT32_MAX)
        throw Error("makePlies: more than 2^32-1 ply points; increase PlyOptions.pitch or reduce samplesPerTurn");
    Plies out;
    out.plyRadius = opt.plyRadius;
    out.centerRadius = opt.centerRadius;
    out.pitch = opt.pitch;
    const size_t curveCount = firstCurve[yarnCount];
    // The two big arrays are allocated (and zero-filled) concurrently.
    tbb::parallel_invoke([&] { out.curves.points.resize(totalPoints); }, [&] { out.radial.resize(totalPoints); });
    out.curves.offsets.reserve(curveCount + 1);
    out.curves.closed.reserve(curveCount);
    out.yarnOfCurve.reserve(curveCount);
    out.plyOfCurve.reserve(curveCount);
    for (size_t y = 0; y < yarnCount; ++y) {
        for (size_t i = firstCurve[y]; i < firstCurve[y + 1]; ++i) {
            out.curves.offsets.push_back(out.curves.offsets.back() + C.size(y));
            out.curves.closed.push_back(C.closed[y]);
            out.yarnOfCurve.push_back(static_cast<uint32_t>(y));
            out.plyOfCurve.push_back(static_cast<uint8_t>(i - firstCurve[y]));
        }
    }

    // Phase offsets 2 pi i / n of the plies.
    std::vector<double> cosPly(n), sinPly(n);
    for (uint32_t i = 0; i < n; ++i) {
        cosPly[i] = std::cos(2.0 * kPi * i / n);
        sinPly[i] = std::sin(2.0 * kPi * i / n);
    }
    const double handed = opt.twist == Twist::Z ? 1.0 : -1.0;
    const double R = opt.centerRadius;

    // Step 3: per yarn (independent: deterministic), RMF frames into per-task buffers, then
    // sweep the helices.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarnCount), [&](const tbb::blocked_range<size_t>& range) {
        std::vector<double> arc;
        std::vector<dvec3> tangent, normal;
        for (size_t y = range.begin(); y < range.end(); ++y) {
            if (firstCurve[y + 1] == firstCurve[y]) continue;
            const uint32_t b = C.begin(y);
            const size_t m = C.size(y);
            const dvec3* X = C.points.data() + b;
            tangent.resize(m);
            normal.resize(m);
            curveFrames(X, m, C.isClosed(y), haveSeeds ? rs.normals.data() + b : nullptr, tangent.data(), normal.data());
            const dvec3* T = tangent.data();
            const dvec3* N = normal.data();
            // Arc length of each resampled point.
            arc.resize(m);
            arc[0] = 0.0;
            for (size_t j = 1; j < m; ++j) arc[j] = arc[j - 1] + glm::length(X[j] - X[j - 1]);
            double pitch = opt.pitch;
            if (C.isClosed(y)) {
                // Integer number of turns so the helix closes.
                const double length = arc[m - 1] + glm::length(X[0] - X[m - 1]);
                const double turns = std::max(1.0, std::round(length / opt.pitch));
                pitch = length / turns;
            }
            const double rate = handed * 2.0 * kPi / pitch;  // dtheta/ds
            const size_t base = out.curves.offsets[firstCurve[y]];
            dvec3* P = out.curves.points.data() + base;
            dvec3* D = out.radial.data() + base;
            for (size_t j = 0; j < m; ++j) {
                const double theta = rate * arc[j];
                const double ct = std::cos(theta), st = std::sin(theta);
                const dvec3 nj = N[j];
                const dvec3 bj = glm::cross(T[j], nj);
                const dvec3 xj = X[j];
                for (uint32_t i = 0; i < n; ++i) {
                    const double c = ct * cosPly[i] - st * sinPly[i];  // cos(theta + 2 pi i / n)
                    const double s = st * cosPly[i] + ct * sinPly[i];  // sin(theta + 2 pi i / n)
                    const dvec3 radial = c * nj + s * bj;
                    P[i * m + j] = xj + R * radial;
                    D[i * m + j] = radial;
                }
            }
        }
    });
    return out;
}

}  // namespace knit
