// bakePlies: the yarns of the tiles around pattern cell (0, 0), flat in z = 0, and their plies,
// each yarn's pitch adjusted until one period of the yarn holds a whole number of ply turns.
#include "bake_plies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/stitch.hpp"
#include "knit/tiling.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

using util::kTwoPi;

// The stitched yarns of the tiles around cells (0, 0) to (1, 1) (a cell baked from a shifted origin), in pattern metres, lying in z = 0.
MappedYarns flatYarns(const Pattern& pattern, int margin) {
    const TileReach reach = tileReach(pattern);
    const Tiling tiling = tilesForRegion(-reach.hi - glm::ivec2(1 + margin), -reach.lo + glm::ivec2(2 + margin));
    PatternPlacement placement;  // one period per unit of uv, pattern size: uv * period = pattern x, y
    const UvYarns uv = stitchYarns(pattern, buildAdjacency(pattern), tiling, placement);
    MappedYarns out;
    for (size_t y = 0; y < uv.yarnCount(); ++y) {
        std::vector<glm::dvec3> points;
        for (uint32_t k = uv.offsets[y]; k < uv.offsets[y + 1]; ++k)
            points.emplace_back(uv.uv[k].x * pattern.px, uv.uv[k].y * pattern.py, uv.height[k]);
        out.curves.addCurve(points.data(), points.size(), uv.closed[y] != 0);
    }
    out.normals.assign(out.curves.pointCount(), glm::dvec3(0, 0, 1));
    return out;
}

MappedYarns oneYarn(const MappedYarns& all, size_t y) {
    MappedYarns out;
    const uint32_t b = all.curves.begin(y), n = all.curves.size(y);
    out.curves.addCurve(all.curves.points.data() + b, n, all.curves.isClosed(y));
    out.normals.assign(all.normals.begin() + b, all.normals.begin() + b + n);
    return out;
}

double wrapAngle(double a) { return std::remainder(a, kTwoPi); }

// How far the ply phase of a yarn advances over one period of the pattern: ply 0's radial
// direction at the centre point nearest `centre` against the one a period further along the
// yarn (the first of the four period translations that lands on the yarn within `tolerance`).
struct PeriodPhase {
    bool found = false;
    double delta = 0;   // radians, wrapped to (-pi, pi], positive = right-handed about the tangent
    double length = 0;  // arc length of the yarn over the period (metres)
};

PeriodPhase periodPhase(const Plies& plies, glm::dvec2 period, glm::dvec2 centre, double tolerance) {
    PeriodPhase out;
    const Polylines& c = plies.curves;
    if (c.curveCount() == 0 || c.size(0) < 4) return out;
    const uint32_t b = c.begin(0), n = c.size(0);
    std::vector<glm::dvec3> axis(n);
    std::vector<double> arc(n, 0.0);
    for (uint32_t i = 0; i < n; ++i) axis[i] = c.points[b + i] - plies.centerRadius * plies.radial[b + i];
    for (uint32_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + glm::length(axis[i] - axis[i - 1]);
    uint32_t i0 = 1;
    for (uint32_t i = 1; i + 1 < n; ++i)
        if (glm::length(glm::dvec2(axis[i]) - centre) < glm::length(glm::dvec2(axis[i0]) - centre)) i0 = i;
    const glm::dvec2 shifts[4] = {{period.x, 0}, {-period.x, 0}, {0, period.y}, {0, -period.y}};
    double best = tolerance;
    uint32_t bestK = 0;
    double bestT = 0;
    for (const glm::dvec2& shift : shifts) {
        const glm::dvec3 target = axis[i0] + glm::dvec3(shift, 0.0);
        for (uint32_t k = 0; k + 1 < n; ++k) {
            const glm::dvec3 d = axis[k + 1] - axis[k];
            const double dd = glm::dot(d, d);
            const double t = dd > 0 ? std::clamp(glm::dot(target - axis[k], d) / dd, 0.0, 1.0) : 0.0;
            const double dist = glm::length(axis[k] + t * d - target);
            if (dist < best) best = dist, bestK = k, bestT = t;
        }
    }
    if (!(best < tolerance)) return out;
    const glm::dvec3 tangent = glm::normalize(axis[i0 + 1] - axis[i0 - 1]);
    auto across = [&](const glm::dvec3& r) { return glm::normalize(r - glm::dot(r, tangent) * tangent); };
    const glm::dvec3 rA = across(plies.radial[b + i0]);
    const glm::dvec3 rB = across((1 - bestT) * plies.radial[b + bestK] + bestT * plies.radial[b + bestK + 1]);
    const double sB = arc[bestK] + bestT * (arc[bestK + 1] - arc[bestK]);
    // Phase from the earlier point to the later one along the curve (the helix's direction).
    const glm::dvec3 from = sB >= arc[i0] ? rA : rB, to = sB >= arc[i0] ? rB : rA;
    out.found = true;
    out.delta = wrapAngle(std::atan2(glm::dot(tangent, glm::cross(from, to)), glm::dot(from, to)));
    out.length = std::abs(sB - arc[i0]);
    return out;
}

// The pitch closest to `pitch` whose ply phase over one period is a whole number of turns
// (the twist sign: Z turns right-handed about the tangent, S left-handed).
double periodicPitch(double pitch, const PeriodPhase& phase, Twist twist) {
    const double sign = twist == Twist::Z ? 1.0 : -1.0;
    double bestInverse = 1.0 / pitch;
    double bestChange = std::numeric_limits<double>::max();
    for (int turns = -1; turns <= 1; ++turns) {
        const double inverse = 1.0 / pitch - sign * (phase.delta + turns * kTwoPi) / (kTwoPi * phase.length);
        if (inverse > 0.25 / pitch && std::abs(inverse - 1.0 / pitch) < bestChange)
            bestChange = std::abs(inverse - 1.0 / pitch), bestInverse = inverse;
    }
    return 1.0 / bestInverse;
}

void appendPlies(Plies& all, const Plies& more, uint32_t yarn) {
    for (size_t c = 0; c < more.curves.curveCount(); ++c) {
        const uint32_t b = more.curves.begin(c);
        all.curves.addCurve(more.curves.points.data() + b, more.curves.size(c), more.curves.isClosed(c));
        all.yarnOfCurve.push_back(yarn);
        all.plyOfCurve.push_back(more.plyOfCurve[c]);
    }
    all.radial.insert(all.radial.end(), more.radial.begin(), more.radial.end());
    all.plyRadius = more.plyRadius, all.centerRadius = more.centerRadius, all.pitch = more.pitch;
}

}  // namespace

BakePlies bakePlies(const Pattern& pattern, const PlyOptions& options, bool periodic, int margin) {
    // Step 1: resolve the ply options at the pattern's yarn radius.
    PlyOptions po = options;
    if (po.yarnRadius == 0.0) po.yarnRadius = pattern.radius;
    po = resolvePlyOptions(po);
    BakePlies out;
    out.yarnRadius = po.yarnRadius;
    out.zMin = std::numeric_limits<double>::max(), out.zMax = -out.zMin;
    for (const glm::dvec3& p : pattern.points) out.zMin = std::min(out.zMin, p.z), out.zMax = std::max(out.zMax, p.z);
    out.zMin -= po.yarnRadius, out.zMax += po.yarnRadius;
    // Step 2: the flat yarns of the tiles around the cell.
    const MappedYarns yarns = flatYarns(pattern, margin);
    if (yarns.curves.curveCount() == 0) throw Error("bake: pattern '" + pattern.name + "' has no yarns to bake");
    // Step 3: per yarn, plies whose phase repeats with the period (a few corrections of the pitch:
    // the resampling, and so the frame's rotation over the period, moves slightly with it).
    const glm::dvec2 period(pattern.px, pattern.py), centre = 0.5 * period;
    for (size_t y = 0; y < yarns.curves.curveCount(); ++y) {
        const MappedYarns one = oneYarn(yarns, y);
        PlyOptions yo = po;
        Plies plies = makePlies(one, yo);
        for (int round = 0; periodic && round < 4; ++round) {
            const PeriodPhase phase = periodPhase(plies, period, centre, 0.1 * po.yarnRadius);
            if (!phase.found || std::abs(phase.delta) < 1e-4) break;
            yo.pitch = periodicPitch(yo.pitch, phase, yo.twist);
            plies = makePlies(one, yo);
        }
        out.yarnPitch.push_back(yo.pitch);
        appendPlies(out.plies, plies, static_cast<uint32_t>(y));
    }
    return out;
}

}  // namespace knit
