// plies_curves.hpp — test curves shared by the resample, frames and plies tests (made in code).
#pragma once
#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/resample.hpp"
#include "util/math.hpp"

namespace knit::test {

// Appends one yarn to `y` with the same surface normal at every point.
inline void addYarn(MappedYarns& y, const std::vector<glm::dvec3>& pts, bool closed,
                    glm::dvec3 normal = glm::dvec3(0, 0, 1)) {
    y.curves.addCurve(pts.data(), pts.size(), closed);
    y.normals.insert(y.normals.end(), pts.size(), normal);
}

// `count` points on a circle of `radius` in the plane z = 0 (each stored once: a closed curve).
inline std::vector<glm::dvec3> circle(double radius, int count) {
    std::vector<glm::dvec3> p;
    for (int i = 0; i < count; ++i) {
        const double a = util::kTwoPi * i / count;
        p.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
    }
    return p;
}

// (2,3) torus knot: a closed space curve whose RMF does not close by itself.
inline std::vector<glm::dvec3> torusKnot(int count, double scale) {
    std::vector<glm::dvec3> p;
    for (int i = 0; i < count; ++i) {
        const double t = util::kTwoPi * i / count;
        p.push_back(scale * glm::dvec3((2.0 + std::cos(3 * t)) * std::cos(2 * t),
                                       (2.0 + std::cos(3 * t)) * std::sin(2 * t), std::sin(3 * t)));
    }
    return p;
}

}  // namespace knit::test
