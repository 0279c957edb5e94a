// Contact pairs of a periodic yarn cell: closest points of two segments, neighbours along a
// yarn, and the spatial hash over the periodic images (see relax_contact.hpp).
#include "relax_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/geometric.hpp>

#include "knit/error.hpp"

namespace knit::relax {

YarnIndex indexYarns(const Pattern& p, const std::vector<Seg>& segs) {
    const size_t n = p.points.size();
    // Out/in segment per vertex: every yarn must be a closed, consistently oriented cycle.
    std::vector<int32_t> out(n, -1);
    for (size_t i = 0; i < segs.size(); ++i) {
        if (out[segs[i].a] >= 0)
            throw Error(p.name + ": relaxation needs closed yarns with consistently oriented edges (vertex " +
                        std::to_string(segs[i].a) + ")");
        out[segs[i].a] = int32_t(i);
    }
    YarnIndex yi;
    for (auto* v : {&yi.yarn, &yi.index, &yi.ux, &yi.uy}) v->assign(n, -1);
    for (size_t start = 0; start < n; ++start) {
        if (yi.yarn[start] >= 0) continue;
        const int32_t y = int32_t(yi.length.size());
        int32_t count = 0, ux = 0, uy = 0;
        for (size_t v = start; yi.yarn[v] < 0;) {
            if (out[v] < 0)
                throw Error(p.name + ": relaxation needs closed yarns (vertex " + std::to_string(v) + " ends a yarn)");
            yi.yarn[v] = y;
            yi.index[v] = count++;
            yi.ux[v] = ux;
            yi.uy[v] = uy;
            const Seg& s = segs[size_t(out[v])];
            ux += s.dx;
            uy += s.dy;
            v = s.b;
            if (v != start && yi.yarn[v] >= 0)
                throw Error(p.name + ": yarns of the pattern merge at vertex " + std::to_string(v));
        }
        yi.length.push_back(count);
        yi.wx.push_back(ux);
        yi.wy.push_back(uy);
    }
    return yi;
}

bool nearAlongYarn(const YarnIndex& yi, const std::vector<Seg>& segs, const Pair& pr, int gap) {
    const uint32_t a = segs[pr.s].a, b = segs[pr.t].a;
    const int32_t y = yi.yarn[a];
    if (yi.yarn[b] != y) return false;
    // Copy offset between the two vertices' copies of the yarn: a multiple m of the winding.
    const int32_t cx = pr.ix - yi.ux[b] + yi.ux[a], cy = pr.iy - yi.uy[b] + yi.uy[a];
    const int32_t wx = yi.wx[size_t(y)], wy = yi.wy[size_t(y)], len = yi.length[size_t(y)];
    long delta = yi.index[b] - yi.index[a];
    if (wx == 0 && wy == 0) {
        if (cx != 0 || cy != 0) return false;
        delta = std::abs(delta) % len;
        delta = std::min<long>(delta, len - delta);
    } else {
        const int32_t m = wx != 0 ? cx / wx : cy / wy;
        if (cx != m * wx || cy != m * wy) return false;
        delta = std::abs(delta + long(m) * len);
    }
    return delta <= gap;
}

void closestParameters(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0, const glm::dvec3& q1,
                       double& s, double& t) {
    // C. Ericson, Real-Time Collision Detection, 5.1.9.
    const glm::dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    const double eps = 1e-18;
    if (a <= eps && e <= eps) {
        s = t = 0;
        return;
    }
    if (a <= eps) {
        s = 0;
        t = std::clamp(f / e, 0.0, 1.0);
        return;
    }
    const double c = glm::dot(d1, r);
    if (e <= eps) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
        return;
    }
    const double b = glm::dot(d1, d2), denom = a * e - b * b;
    s = denom > eps ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    t = (b * s + f) / e;
    if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
}

namespace {

struct Grid {
    int nx = 1, ny = 1;
    double wx = 1, wy = 1;
    std::vector<std::vector<uint32_t>> cells;
};

int floorDiv(double v, double p) { return int(std::floor(v / p)); }

// Centreline distance of segment s and segment t moved by `shift`: the midpoint test alone keeps
// pairs up to two segment lengths farther than the cutoff (long cable legs: ten times too many).
double segmentDistance(const std::vector<glm::dvec3>& x, double px, double py, const Seg& s, const Seg& t,
                       const glm::dvec3& shift) {
    const glm::dvec3 p0 = x[s.a], p1 = x[s.b] + glm::dvec3(s.dx * px, s.dy * py, 0);
    const glm::dvec3 q0 = x[t.a] + shift, q1 = x[t.b] + glm::dvec3(t.dx * px, t.dy * py, 0) + shift;
    double a = 0, b = 0;
    closestParameters(p0, p1, q0, q1, a, b);
    return glm::length((p0 + a * (p1 - p0)) - (q0 + b * (q1 - q0)));
}

}  // namespace

std::vector<Pair> findPairs(const std::vector<glm::dvec3>& x, double px, double py, const std::vector<Seg>& segs,
                            const YarnIndex& yi, double cutoff) {
    // Step 1: segment midpoints wrapped into the cell, and the largest half length.
    const size_t m = segs.size();
    std::vector<glm::dvec3> mid(m);
    std::vector<int> fx(m), fy(m);
    double half = 0;
    for (size_t i = 0; i < m; ++i) {
        const glm::dvec3 p = x[segs[i].a], q = x[segs[i].b] + glm::dvec3(segs[i].dx * px, segs[i].dy * py, 0);
        mid[i] = 0.5 * (p + q);
        half = std::max(half, 0.5 * glm::length(q - p));
        fx[i] = floorDiv(mid[i].x, px);
        fy[i] = floorDiv(mid[i].y, py);
    }
    // Step 2: the hash; a cell is at least as wide as the farthest midpoint distance of a pair.
    const double reach = cutoff + 2 * half;
    Grid g;
    g.nx = std::max(1, int(px / reach));
    g.ny = std::max(1, int(py / reach));
    g.wx = px / g.nx;
    g.wy = py / g.ny;
    g.cells.assign(size_t(g.nx) * size_t(g.ny), {});
    std::vector<int> cx(m), cy(m);
    for (size_t i = 0; i < m; ++i) {
        cx[i] = std::clamp(int((mid[i].x - fx[i] * px) / g.wx), 0, g.nx - 1);
        cy[i] = std::clamp(int((mid[i].y - fy[i] * py) / g.wy), 0, g.ny - 1);
        g.cells[size_t(cy[i]) * size_t(g.nx) + size_t(cx[i])].push_back(uint32_t(i));
    }
    // Step 3: each segment against the 3 x 3 neighbouring cells, with the image they wrap to.
    std::vector<Pair> pairs;
    for (size_t s = 0; s < m; ++s)
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const int ci = cx[s] + di, cj = cy[s] + dj;
                const int wrapX = floorDiv(ci, g.nx), wrapY = floorDiv(cj, g.ny);
                const auto& cell = g.cells[size_t(cj - wrapY * g.ny) * size_t(g.nx) + size_t(ci - wrapX * g.nx)];
                for (uint32_t t : cell) {
                    const Pair pr{uint32_t(s), t, wrapX + fx[s] - fx[t], wrapY + fy[s] - fy[t]};
                    if (t < s || (t == s && (pr.iy < 0 || (pr.iy == 0 && pr.ix <= 0)))) continue;
                    const glm::dvec3 shift(pr.ix * px, pr.iy * py, 0);
                    if (glm::length(mid[t] + shift - mid[s]) > reach) continue;
                    if (nearAlongYarn(yi, segs, pr, 3)) continue;
                    if (segmentDistance(x, px, py, segs[s], segs[t], shift) > cutoff) continue;
                    pairs.push_back(pr);
                }
            }
    return pairs;
}

}  // namespace knit::relax
