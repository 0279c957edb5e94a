// Contact pairs of a periodic yarn cell: closest points of two segments, neighbours along a
// yarn, and the spatial hash over the periodic images (see relax_contact.hpp).
#include "relax_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <tuple>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/error.hpp"

namespace knit::relax {

YarnIndex indexYarns(const Pattern& p, const std::vector<Seg>& segs, bool allowOpen) {
    const size_t n = p.points.size();
    // Out/in segment per vertex: every yarn a consistently oriented cycle, or (allowOpen) path.
    std::vector<int32_t> out(n, -1);
    std::vector<bool> arrives(n, false);
    for (size_t i = 0; i < segs.size(); ++i) {
        if (out[segs[i].a] >= 0)
            throw Error(p.name + ": relaxation needs closed yarns with consistently oriented edges (vertex " +
                        std::to_string(segs[i].a) + ")");
        out[segs[i].a] = int32_t(i);
        arrives[segs[i].b] = true;
    }
    YarnIndex yi;
    for (auto* v : {&yi.yarn, &yi.index, &yi.ux, &yi.uy}) v->assign(n, -1);
    // Open yarns first, from their first vertex (no segment arrives there), then the closed ones.
    auto walk = [&](size_t start, bool open) {
        const int32_t y = int32_t(yi.length.size());
        int32_t count = 0, ux = 0, uy = 0;
        for (size_t v = start; yi.yarn[v] < 0;) {
            yi.yarn[v] = y;
            yi.index[v] = count++;
            yi.ux[v] = ux;
            yi.uy[v] = uy;
            if (out[v] < 0) {
                if (!open)
                    throw Error(p.name + ": relaxation needs closed yarns (vertex " + std::to_string(v) +
                                " ends a yarn)");
                break;
            }
            const Seg& s = segs[size_t(out[v])];
            ux += s.dx;
            uy += s.dy;
            v = s.b;
            if (v != start && yi.yarn[v] >= 0)
                throw Error(p.name + ": yarns of the pattern merge at vertex " + std::to_string(v));
        }
        yi.length.push_back(count);
        yi.wx.push_back(open ? 0 : ux);
        yi.wy.push_back(open ? 0 : uy);
        yi.open.push_back(open);
    };
    for (size_t start = 0; start < n; ++start)
        if (!arrives[start]) {
            if (!allowOpen)
                throw Error(p.name + ": relaxation needs closed yarns (vertex " + std::to_string(start) +
                            " starts a yarn)");
            walk(start, true);
        }
    for (size_t start = 0; start < n; ++start)
        if (yi.yarn[start] < 0) walk(start, false);
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
    if (yi.open[size_t(y)]) {  // one copy of an open yarn: no wrap along it
        if (cx != 0 || cy != 0) return false;
        delta = std::abs(delta);
    } else if (wx == 0 && wy == 0) {
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

// The spatial hash: cells of one period, each listing the segments whose box reaches it, with the
// period (ox, oy) the box's part in that cell wraps from.
struct Entry {
    uint32_t t = 0;
    int32_t ox = 0, oy = 0;
};
struct Grid {
    int nx = 1, ny = 1;
    double wx = 1, wy = 1;
    std::vector<std::vector<Entry>> cells;
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

// A segment's box: its wrapped midpoint +- e (the half length beyond the typical one), as a
// range of cells, unwrapped.
struct CellRange {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};
CellRange cellsOf(const Grid& g, const glm::dvec3& wrappedMid, double e) {
    return {int(std::floor((wrappedMid.x - e) / g.wx)), int(std::floor((wrappedMid.x + e) / g.wx)),
            int(std::floor((wrappedMid.y - e) / g.wy)), int(std::floor((wrappedMid.y + e) / g.wy))};
}

std::vector<Pair> findPairs(const std::vector<glm::dvec3>& x, double px, double py, const std::vector<Seg>& segs,
                            const YarnIndex& yi, double cutoff) {
    // Step 1: segment midpoints, their period (fx, fy) and half lengths; the typical half length
    // (90th percentile): long segments (cable legs) are listed in every cell their box reaches
    // instead of making every cell as wide as the longest one.
    const size_t m = segs.size();
    std::vector<glm::dvec3> mid(m), wrapped(m);
    std::vector<double> half(m);
    std::vector<int> fx(m), fy(m);
    for (size_t i = 0; i < m; ++i) {
        const glm::dvec3 p = x[segs[i].a], q = x[segs[i].b] + glm::dvec3(segs[i].dx * px, segs[i].dy * py, 0);
        mid[i] = 0.5 * (p + q);
        half[i] = 0.5 * glm::length(q - p);
        fx[i] = floorDiv(mid[i].x, px);
        fy[i] = floorDiv(mid[i].y, py);
        wrapped[i] = mid[i] - glm::dvec3(fx[i] * px, fy[i] * py, 0);
    }
    std::vector<double> sorted = half;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(9 * m / 10), sorted.end());
    const double typical = m ? sorted[9 * m / 10] : 0.0;
    auto excess = [&](size_t i) { return std::max(0.0, half[i] - typical); };
    // Step 2: the hash. Two segments closer than the cutoff have boxes less than `width` apart
    // along x and y (|mid_s - mid_t| <= cutoff + half_s + half_t), so their cells are at most
    // `reach` cells apart: 1 when the period holds a cell of that width, more when the period is
    // narrower than it (a cutoff beyond the period: pairs with images two or more periods away).
    const double width = cutoff + 2 * typical;
    Grid g;
    g.nx = std::max(1, int(px / width));
    g.ny = std::max(1, int(py / width));
    g.wx = px / g.nx;
    g.wy = py / g.ny;
    const int reachX = std::max(1, int(std::ceil(width / g.wx))), reachY = std::max(1, int(std::ceil(width / g.wy)));
    g.cells.assign(size_t(g.nx) * size_t(g.ny), {});
    for (size_t t = 0; t < m; ++t) {
        const CellRange r = cellsOf(g, wrapped[t], excess(t));
        for (int j = r.j0; j <= r.j1; ++j)
            for (int i = r.i0; i <= r.i1; ++i) {
                const int ox = floorDiv(i, g.nx), oy = floorDiv(j, g.ny);
                g.cells[size_t(j - oy * g.ny) * size_t(g.nx) + size_t(i - ox * g.nx)].push_back({uint32_t(t), ox, oy});
            }
    }
    // Step 3: each segment against the cells next to its box, with the image they wrap to; in
    // parallel, each segment into its own sorted list, joined in segment order (the same list for
    // any number of threads).
    std::vector<std::vector<Pair>> found(m);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, m, 64), [&](const tbb::blocked_range<size_t>& range) {
        std::vector<Pair> candidates;
        for (size_t s = range.begin(); s != range.end(); ++s) {
            candidates.clear();
            const CellRange r = cellsOf(g, wrapped[s], excess(s));
            for (int cj = r.j0 - reachY; cj <= r.j1 + reachY; ++cj)
                for (int ci = r.i0 - reachX; ci <= r.i1 + reachX; ++ci) {
                    const int wrapX = floorDiv(ci, g.nx), wrapY = floorDiv(cj, g.ny);
                    for (const Entry& en :
                         g.cells[size_t(cj - wrapY * g.ny) * size_t(g.nx) + size_t(ci - wrapX * g.nx)]) {
                        const Pair pr{uint32_t(s), en.t, wrapX - en.ox + fx[s] - fx[en.t],
                                      wrapY - en.oy + fy[s] - fy[en.t]};
                        if (en.t < s || (en.t == s && (pr.iy < 0 || (pr.iy == 0 && pr.ix <= 0)))) continue;
                        const glm::dvec3 shift(pr.ix * px, pr.iy * py, 0);
                        if (glm::length(mid[en.t] + shift - mid[s]) > cutoff + half[s] + half[en.t]) continue;
                        candidates.push_back(pr);
                    }
                }
            // A long segment is listed in several cells: each pair once.
            std::sort(candidates.begin(), candidates.end(), [](const Pair& a, const Pair& b) {
                return std::tie(a.t, a.ix, a.iy) < std::tie(b.t, b.ix, b.iy);
            });
            for (size_t k = 0; k < candidates.size(); ++k) {
                const Pair& pr = candidates[k];
                if (k > 0 && pr.t == candidates[k - 1].t && pr.ix == candidates[k - 1].ix &&
                    pr.iy == candidates[k - 1].iy)
                    continue;
                if (nearAlongYarn(yi, segs, pr, 3)) continue;
                if (segmentDistance(x, px, py, segs[s], segs[pr.t], glm::dvec3(pr.ix * px, pr.iy * py, 0)) > cutoff)
                    continue;
                found[s].push_back(pr);
            }
        }
    });
    std::vector<Pair> pairs;
    for (const std::vector<Pair>& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
    return pairs;
}

}  // namespace knit::relax
