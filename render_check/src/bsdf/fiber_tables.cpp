// Fiber tables by 2D ray casting into a ring of fibers (and a ring of plies), plus the shading frame.
#include "knit/fiber_tables.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "util/math.hpp"

namespace knit {
namespace {

using util::kPi;

struct Ring {
    std::vector<glm::dvec2> centres;
    double radius = 0;  // of each circle
};

// n touching circles around the origin filling the unit disk.
Ring touchingRing(int n) {
    Ring ring;
    const double s = std::sin(kPi / n);
    const double centre = 1.0 / (1.0 + s);
    ring.radius = n == 1 ? 1.0 : centre * s;
    for (int k = 0; k < n; ++k) {
        const double a = 2.0 * kPi * k / n;
        ring.centres.push_back(n == 1 ? glm::dvec2(0.0) : centre * glm::dvec2(std::cos(a), std::sin(a)));
    }
    return ring;
}

// First intersection t > tMin of the ray o + t d (|d| = 1) with circle (c, r), or -1.
double hitCircle(glm::dvec2 o, glm::dvec2 d, glm::dvec2 c, double r, double tMin) {
    const glm::dvec2 oc = o - c;
    const double b = glm::dot(d, oc), cc = glm::dot(oc, oc) - r * r;
    const double disc = b * b - cc;
    if (disc < 0) return -1;
    const double sq = std::sqrt(disc);
    if (-b - sq > tMin) return -b - sq;
    if (-b + sq > tMin) return -b + sq;
    return -1;
}

// Fraction of stratified rays over the half-plane around n, from p, blocked by a circle of the ring
// other than `self` within `length`.
double blockedFraction(const Ring& ring, int self, glm::dvec2 p, glm::dvec2 n, int rays, double length) {
    // Only circles some ray can reach within `length`: not farther than that, and not wholly
    // behind p (every ray leaves into the half-plane of n). The others cannot block any ray, so
    // skipping them leaves the count as it was (a third of the 40 fibers remain).
    std::vector<glm::dvec2> near;
    for (size_t k = 0; k < ring.centres.size(); ++k) {
        const glm::dvec2 pc = ring.centres[k] - p;
        if (static_cast<int>(k) != self && glm::length(pc) < length + ring.radius && glm::dot(pc, n) > -ring.radius)
            near.push_back(ring.centres[k]);
    }
    const double base = std::atan2(n.y, n.x);
    int blocked = 0;
    for (int j = 0; j < rays; ++j) {
        const double a = base - 0.5 * kPi + kPi * (j + 0.5) / rays;
        const glm::dvec2 d(std::cos(a), std::sin(a));
        for (const glm::dvec2& c : near) {
            const double t = hitCircle(p, d, c, ring.radius, 1e-3);
            if (t > 0 && t < length) {
                ++blocked;
                break;
            }
        }
    }
    return double(blocked) / rays;
}

// Min-max normalise blocked fractions, invert, remap with the floor.
void toShadow(const std::vector<double>& blocked, double floor, std::vector<float>& out) {
    const auto [lo, hi] = std::minmax_element(blocked.begin(), blocked.end());
    out.resize(blocked.size());
    for (size_t i = 0; i < blocked.size(); ++i) {
        const double s = *hi > *lo ? 1.0 - (blocked[i] - *lo) / (*hi - *lo) : 1.0;
        out[i] = static_cast<float>(s * (1.0 - floor) + floor);
    }
}

double wrapAngle(double a) { return std::remainder(a, 2.0 * kPi); }

double frac(double x) { return x - std::floor(x); }

// A unit vector perpendicular to unit t, for degenerate shading frames. Not util::anyPerpendicular:
// that one picks another axis (least aligned with t, then projects), and the frames rendered so far
// were built with this rule (the x axis, or y when |t.x| >= 0.9; crossed with t).
glm::dvec3 anyPerpendicular(const glm::dvec3& t) {
    const glm::dvec3 a = std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(t, a));
}

// The ply shadow seen from outside the ring of plies: parallel 2D rays from `directions` angles,
// `across` offsets over the ring's width each; per first hit, the ply table at the hit's angle
// from that ply's radial direction. (The twist turns the ring along the yarn: every direction
// across it is seen.)
double visiblePlyShadow(const Ring& plies, const FiberTables& t) {
    const int directions = 64, across = 64;
    double sum = 0;
    int hits = 0;
    for (int i = 0; i < directions; ++i) {
        const double b = 2.0 * kPi * (i + 0.5) / directions;
        const glm::dvec2 out(std::cos(b), std::sin(b)), side(-out.y, out.x);
        for (int j = 0; j < across; ++j) {
            const glm::dvec2 o = 2.0 * out + (-1.0 + 2.0 * (j + 0.5) / across) * side;
            int best = -1;
            double bestT = 1e30;
            for (size_t k = 0; k < plies.centres.size(); ++k) {
                const double th = hitCircle(o, -out, plies.centres[k], plies.radius, 0.0);
                if (th > 0 && th < bestT) bestT = th, best = static_cast<int>(k);
            }
            if (best < 0) continue;
            const glm::dvec2 n = o - bestT * out - plies.centres[best];
            const glm::dvec2 c = plies.centres[best];
            const double radialAngle = glm::length(c) > 0 ? std::atan2(c.y, c.x) : 0.0;
            sum += t.ply(frac((std::atan2(n.y, n.x) - radialAngle) / (2.0 * kPi)));
            ++hits;
        }
    }
    return hits > 0 ? sum / hits : 1.0;
}

}  // namespace

FiberTableOptions fiberTableOptions(const PlyMaterial& m, int plyCount) {
    FiberTableOptions o;
    o.fiberCount = m.fiberCount;
    o.plyCount = std::max(1, plyCount);
    o.size = m.tableSize;
    o.aoRays = m.aoRays;
    o.fiberShadowFloor = m.fiberShadowFloor;
    o.plyShadowFloor = m.plyShadowFloor;
    return o;
}

FiberTables buildFiberTables(const FiberTableOptions& o) {
    FiberTables t;
    t.size = std::max(1, o.size);
    const Ring fibers = touchingRing(std::max(3, o.fiberCount));
    t.ringRadius = glm::length(fibers.centres[0]);
    t.fiberRadius = fibers.radius;
    t.delta.resize(t.size);
    t.phase.resize(t.size);
    std::vector<double> blockedFiber(t.size), blockedPly(t.size);
    const Ring plies = touchingRing(std::max(1, o.plyCount));
    tbb::parallel_for(tbb::blocked_range<int>(0, t.size), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i < r.end(); ++i) {
            const double a = 2.0 * kPi * (i + 0.5) / t.size;
            const glm::dvec2 dirOut(std::cos(a), std::sin(a));
            // Step 1: cast a 2D ray from outside towards the ply centre; first fiber hit.
            const glm::dvec2 origin = 2.0 * dirOut, d = -dirOut;
            int best = -1;
            double bestT = 1e30;
            for (size_t k = 0; k < fibers.centres.size(); ++k) {
                const double th = hitCircle(origin, d, fibers.centres[k], fibers.radius, 0.0);
                if (th > 0 && th < bestT) bestT = th, best = static_cast<int>(k);
            }
            glm::dvec2 n = dirOut, hit = origin + bestT * d;
            if (best >= 0) {
                n = glm::normalize(hit - fibers.centres[best]);
                const double c = std::atan2(fibers.centres[best].y, fibers.centres[best].x);
                t.phase[i] = static_cast<float>(wrapAngle(c - a));
            } else {
                hit = dirOut * (t.ringRadius + t.fiberRadius);
                t.phase[i] = 0;
            }
            // Step 2: delta = signed angle from the ply normal to the fiber normal.
            t.delta[i] = static_cast<float>(std::atan2(dirOut.x * n.y - dirOut.y * n.x, glm::dot(dirOut, n)));
            // Step 3: fiber-level occlusion from the hit point.
            blockedFiber[i] = best >= 0 ? blockedFraction(fibers, best, hit + 1e-6 * n, n, o.aoRays, 1.0) : 0.0;
            // Step 4: ply-level occlusion: point at angle a on ply 0 of the yarn's ring of plies
            // (a measured from ply 0's radial direction, the +x axis), rays of one yarn radius.
            const glm::dvec2 p = plies.centres[0] + plies.radius * dirOut;
            blockedPly[i] = o.plyCount > 1 ? blockedFraction(plies, 0, p + 1e-6 * dirOut, dirOut, o.aoRays, 1.0) : 0.0;
        }
    });
    toShadow(blockedFiber, o.fiberShadowFloor, t.fiberShadow);
    toShadow(blockedPly, o.plyShadowFloor, t.plyShadow);
    t.visiblePlyShadow = visiblePlyShadow(plies, t);
    return t;
}

FiberTables::Texel FiberTables::fiber(double u) const {
    Texel x;
    if (size <= 0) return x;
    const double s = frac(u) * size;
    const int i = std::min(size - 1, static_cast<int>(s));
    x.delta = delta[i];
    x.phase = phase[i];
    // Linear interpolation of the shadow between texel centres (wrapping).
    const double c = s - 0.5;
    const int i0 = static_cast<int>(std::floor(c));
    const double w = c - i0;
    const int a = ((i0 % size) + size) % size, b = (a + 1) % size;
    x.shadow = (1.0 - w) * fiberShadow[a] + w * fiberShadow[b];
    return x;
}

double FiberTables::ply(double u) const {
    if (size <= 0) return 1.0;
    const double c = frac(u) * size - 0.5;
    const int i0 = static_cast<int>(std::floor(c));
    const double w = c - i0;
    const int a = ((i0 % size) + size) % size, b = (a + 1) % size;
    return (1.0 - w) * plyShadow[a] + w * plyShadow[b];
}

size_t FiberTables::bytes() const {
    return sizeof(float) * (delta.size() + phase.size() + fiberShadow.size() + plyShadow.size());
}

glm::dvec3 ShadingFrame::toLocal(const glm::dvec3& w) const { return {glm::dot(w, x), glm::dot(w, y), glm::dot(w, z)}; }
glm::dvec3 ShadingFrame::toWorld(const glm::dvec3& w) const { return w.x * x + w.y * y + w.z * z; }

ShadingFrame plyShadingFrame(const PlySurfacePoint& p, const PlyMaterial& m, const FiberTables& tables) {
    ShadingFrame f;
    // Step 1: orthonormal ply frame (N outward, T along the ply).
    const glm::dvec3 n = glm::normalize(p.normal);
    glm::dvec3 t = p.tangent - glm::dot(p.tangent, n) * n;
    t = glm::length(t) > 1e-9 ? glm::normalize(t) : anyPerpendicular(n);
    // Step 2: ply phase phi around the ply, measured from the radial direction about T.
    glm::dvec3 rad = p.radial - glm::dot(p.radial, t) * t;
    double phi = 0;
    if (glm::length(rad) > 1e-9) {
        rad = glm::normalize(rad);
        phi = std::atan2(glm::dot(n, glm::cross(t, rad)), glm::dot(n, rad));
    }
    const double plyShadow = p.bundle ? tables.visiblePlyShadow : tables.ply(phi / (2.0 * kPi));
    if (!m.fiberDetail || tables.size == 0) {
        f.x = t;
        f.z = n;
        f.y = glm::cross(f.z, f.x);
        f.shadow = plyShadow;
        return f;
    }
    // Step 3: table lookup at u = frac((phi + tau_f v) / 2 pi).
    const FiberTables::Texel tex = tables.fiber((phi + m.fiberTwist * p.v) / (2.0 * kPi));
    // Step 4: fiber tangent = helix tangent at the visible fiber's centre (phase offset about T).
    const glm::dvec3 side = glm::cross(t, n);
    const glm::dvec3 nc = std::cos(tex.phase) * n + std::sin(tex.phase) * side;
    const glm::dvec3 tf = glm::normalize(t + tables.ringRadius * m.fiberTwist * glm::cross(t, nc));
    // Step 5: fiber normal = ply normal without its tangential part, rotated about t_f by delta.
    glm::dvec3 np = n - glm::dot(n, tf) * tf;
    np = glm::length(np) > 1e-9 ? glm::normalize(np) : anyPerpendicular(tf);
    const glm::dvec3 nf = std::cos(tex.delta) * np + std::sin(tex.delta) * glm::cross(tf, np);
    f.x = tf;
    f.z = glm::normalize(nf);
    f.y = glm::cross(f.z, f.x);
    f.shadow = tex.shadow * plyShadow;
    return f;
}

}  // namespace knit
