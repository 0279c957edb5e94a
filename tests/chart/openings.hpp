// openings.hpp — the largest opening of a periodic yarn cell seen along z: the radius of the
// largest disc in the plane that no yarn covers (distance to the nearest projected centreline
// segment, any periodic image, minus the yarn radius), in yarn radii. An eyelet's hole.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "knit/pattern.hpp"

namespace knit::test {

inline double pointSegment2(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 d = b - a;
    const double t = std::clamp(glm::dot(p - a, d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
    const glm::dvec2 q = a + t * d - p;
    return glm::dot(q, q);
}

// Centre and radius (in yarn radii) of the largest uncovered disc: a grid search at `step` radii
// over one period, refined at step / 5 around the best point.
struct Opening {
    glm::dvec2 centre{0.0};
    double radius = 0;
};
inline Opening largestOpening(const Pattern& p, double step = 0.25) {
    std::vector<std::pair<glm::dvec2, glm::dvec2>> segs;
    for (const PeriodicEdge& e : p.edges)
        for (int ix = -1; ix <= 1; ++ix)
            for (int iy = -1; iy <= 1; ++iy) {
                const glm::dvec2 shift(ix * p.px, iy * p.py);
                const glm::dvec2 a(p.points[e.v0].x, p.points[e.v0].y);
                const glm::dvec2 b(p.points[e.v1].x + e.dx * p.px, p.points[e.v1].y + e.dy * p.py);
                segs.push_back({a + shift, b + shift});
            }
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
    for (const glm::dvec3& q : p.points) x0 = std::min(x0, q.x), y0 = std::min(y0, q.y);
    auto clearance = [&](glm::dvec2 c) {
        double m = std::numeric_limits<double>::infinity();
        for (const auto& s : segs) m = std::min(m, pointSegment2(c, s.first, s.second));
        return std::sqrt(m) / p.radius - 1.0;
    };
    Opening best{{x0, y0}, -1e300};
    const double h = step * p.radius;
    for (double x = x0; x < x0 + p.px; x += h)
        for (double y = y0; y < y0 + p.py; y += h)
            if (const double c = clearance({x, y}); c > best.radius) best = {{x, y}, c};
    const Opening coarse = best;
    for (double dx = -h; dx <= h; dx += h / 5)
        for (double dy = -h; dy <= h; dy += h / 5)
            if (const double c = clearance(coarse.centre + glm::dvec2(dx, dy)); c > best.radius)
                best = {coarse.centre + glm::dvec2(dx, dy), c};
    return best;
}

}  // namespace knit::test
