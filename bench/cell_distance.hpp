// How far one relaxed cell's yarns lie from another's (knit serve's preview from the full
// relaxation of the same chart, sampled differently): each vertex's distance to the other cell's
// nearest segment, over its periodic images, both ways, in yarn radii. The two cells are first
// put on the same footing: each centred on its vertices' mean, and the first's x and y scaled to
// the second's period (a preview's period may differ by a few per cent; that difference is
// reported on its own). The nearest segment may be another yarn's, so this is a lower bound
// where two yarns touch; it measures how the preview looks, not which yarn is where.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "knit/pattern.hpp"

namespace knit::bench {

struct CellDistance {
    double max = 0, rms = 0;  // over the vertices of both cells, in yarn radii
};

namespace detail {

inline glm::dvec3 centre(const Pattern& p) {
    glm::dvec3 c(0);
    for (const glm::dvec3& x : p.points) c += x;
    return c / double(std::max<size_t>(p.points.size(), 1));
}

// `from`'s vertices, centred and scaled to `to`'s period, against `to`'s segments (centred);
// adds their squared distances to `sum` and returns the largest distance (metres).
inline double oneWay(const Pattern& from, const Pattern& to, double& sum) {
    const glm::dvec3 cf = centre(from), ct = centre(to);
    const glm::dvec3 scale(to.px / from.px, to.py / from.py, 1.0);
    std::vector<glm::dvec3> a, b;  // `to`'s segments, centred
    for (const PeriodicEdge& e : to.edges) {
        a.push_back(to.points[e.v0] - ct);
        b.push_back(to.points[e.v1] - ct + glm::dvec3(e.dx * to.px, e.dy * to.py, 0));
    }
    double largest = 0;
    for (const glm::dvec3& x : from.points) {
        const glm::dvec3 q0 = (x - cf) * scale;
        double best = 1e300;
        for (int ix = -2; ix <= 2; ++ix)
            for (int iy = -2; iy <= 2; ++iy) {
                const glm::dvec3 q = q0 + glm::dvec3(ix * to.px, iy * to.py, 0);
                for (size_t k = 0; k < a.size(); ++k) {
                    const glm::dvec3 u = b[k] - a[k];
                    const double t = std::clamp(glm::dot(q - a[k], u) / std::max(glm::dot(u, u), 1e-300), 0.0, 1.0);
                    const glm::dvec3 d = q - (a[k] + t * u);
                    best = std::min(best, glm::dot(d, d));
                }
            }
        sum += best;
        largest = std::max(largest, std::sqrt(best));
    }
    return largest;
}

}  // namespace detail

// `a` against `b` and `b` against `a` (the largest and the root mean square over both), in `b`'s
// yarn radii.
inline CellDistance cellDistance(const Pattern& a, const Pattern& b) {
    double sum = 0;
    const double largest = std::max(detail::oneWay(a, b, sum), detail::oneWay(b, a, sum));
    const double n = double(a.points.size() + b.points.size());
    return {largest / b.radius, std::sqrt(sum / n) / b.radius};
}

}  // namespace knit::bench
