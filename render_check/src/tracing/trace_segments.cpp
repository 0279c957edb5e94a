// The outward normal of the ply solid at a point of one of its segments.
#include "trace_segments.hpp"

#include <algorithm>

namespace knit {

glm::vec3 axisNormal(const PlyGeometry& pg, uint32_t s, const glm::vec3& p, float& u) {
    const uint32_t j = pg.segments[s];
    const glm::vec3 a(pg.points[j]), b(pg.points[j + 1]);
    const glm::vec3 d = b - a;
    const float dd = glm::dot(d, d);
    const float raw = dd > 0 ? glm::dot(p - a, d) / dd : 0.f;
    u = std::clamp(raw, 0.f, 1.f);
    const glm::vec3 dir = safeNormalize(d);
    const bool capped =
        (raw < 0 && (!pg.hasLeft(s) || sharpJoint(safeNormalize(a - glm::vec3(pg.points[j - 1])), dir))) ||
        (raw > 1 && (!pg.hasRight(s) || sharpJoint(dir, safeNormalize(glm::vec3(pg.points[j + 2]) - b))));
    return safeNormalize(p - (a + (capped ? u : raw) * d));
}

}  // namespace knit
