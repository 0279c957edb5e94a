// Measures of a relaxed cell shared by the relaxation benchmarks.
#pragma once

#include <glm/geometric.hpp>

#include "knit/pattern.hpp"

namespace knit::bench {

// Yarn length times the yarn radius over the period's area (L r / A, docs/charts.md): how tightly
// the cell packs its yarn.
inline double lengthPerArea(const Pattern& p) {
    double L = 0;
    for (const PeriodicEdge& e : p.edges)
        L += glm::length(p.points[e.v1] + glm::dvec3(e.dx * p.px, e.dy * p.py, 0) - p.points[e.v0]);
    return L * p.radius / (p.px * p.py);
}

}  // namespace knit::bench
