// The curves and the surface a scene built for a view renders (see detail_geometry.hpp).
#include "detail_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "knit/error.hpp"
#include "knit/plies.hpp"
#include "knit/scene.hpp"
#include "util/math.hpp"

namespace knit::impl {
namespace {

// The yarn-level pieces as one-ply "plies" of that radius; their radial reference is the surface
// normal (the yarn's outward side).
Plies yarnCurves(const MappedYarns& pieces, double yarnRadius) {
    Plies p;
    p.curves = pieces.curves;
    p.yarnOfCurve.resize(p.curves.curveCount());
    for (size_t c = 0; c < p.yarnOfCurve.size(); ++c) p.yarnOfCurve[c] = uint32_t(c);
    p.plyOfCurve.assign(p.curves.curveCount(), 0);
    p.plyRadius = yarnRadius;
    p.radial = pieces.normals;
    return p;
}

// Appends `more` to `g`, converted to g's scene units (its points keep their own radius).
void append(PlyGeometry& g, const PlyGeometry& more) {
    const float scale = float(more.unit / g.unit);
    const uint32_t pointBase = uint32_t(g.points.size()), segmentBase = uint32_t(g.segments.size());
    const uint32_t curveBase = uint32_t(g.curveSegments.size() - 1);
    for (const glm::vec4& p : more.points) g.points.push_back(p * scale);
    g.radial.insert(g.radial.end(), more.radial.begin(), more.radial.end());
    for (float a : more.arc) g.arc.push_back(a * scale);
    for (uint32_t s : more.segments) g.segments.push_back(s + pointBase);
    g.flags.insert(g.flags.end(), more.flags.begin(), more.flags.end());
    for (uint32_t c : more.curveOfSegment) g.curveOfSegment.push_back(c + curveBase);
    for (size_t c = 1; c < more.curveSegments.size(); ++c)
        g.curveSegments.push_back(more.curveSegments[c] + segmentBase);
}

PlyGeometry emptyGeometry(const glm::dvec3& origin, double unit) {
    PlyGeometry g;
    g.origin = origin;
    g.unit = unit;
    g.radius = 1.0f;
    return g;
}

}  // namespace

// (The full yarn radius made the yarn level 15% too bright on the garment close-up: a round yarn
// covers more than its twisted plies; docs/views.md.)
double yarnLevelRadius(const PlyOptions& resolved) {
    const int n = resolved.count, steps = 720;
    double mean = 0;
    for (int k = 0; k < steps; ++k) {
        const double theta = util::kPi * (k + 0.5) / steps;
        double widest = 0;
        for (int i = 0; i < n; ++i) widest = std::max(widest, std::abs(std::cos(theta + util::kTwoPi * i / n)));
        mean += widest / steps;
    }
    return resolved.plyRadius + resolved.centerRadius * mean;
}

double bundleHelix(const PlyOptions& resolved) {
    if (!(resolved.pitch > 0)) return 0;
    const double k = util::kTwoPi * resolved.centerRadius / resolved.pitch;
    return resolved.twist == Twist::S ? -k : k;
}

PlyGeometry renderCurves(const Scene& scene, const glm::dvec3& origin, double fiberTwist) {
    const bool plies = scene.plies().curves.pointCount() > 0;
    const MappedYarns* yarnLevel = scene.detail() ? &scene.detail()->pieces.yarns : nullptr;
    const bool yarns = yarnLevel != nullptr && yarnLevel->curves.pointCount() > 0;
    if (!yarns)
        return plies ? buildPlyGeometry(scene.plies(), origin, fiberTwist)
                     : emptyGeometry(origin, resolvePlyOptions(scene.plyOptions()).plyRadius);
    const PlyOptions resolved = resolvePlyOptions(scene.plyOptions());
    const double radius = yarnLevelRadius(resolved);
    PlyGeometry y = buildPlyGeometry(yarnCurves(*yarnLevel, radius), origin, fiberTwist);
    y.firstBundleSegment = 0;
    y.bundleHelix = bundleHelix(resolved);
    if (!plies) return y;
    PlyGeometry g = buildPlyGeometry(scene.plies(), origin, fiberTwist);
    g.firstBundleSegment = g.segmentCount();
    g.bundleHelix = y.bundleHelix;
    append(g, y);
    return g;
}

BaseMesh surfaceMesh(const Scene& scene) {
    static const std::vector<uint32_t> none;
    return meshSubset(scene.mesh(), scene.detail() ? scene.detail()->pieces.surfaceFaces : none, " (surface level)");
}

}  // namespace knit::impl
