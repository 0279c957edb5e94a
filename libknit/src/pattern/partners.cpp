// Partner-endpoint search (Montazeri et al. 2021): turn open curves in one cell into a periodic
// pattern by joining every curve end to the closest end of a curve in a neighbouring cell.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "knit/error.hpp"
#include "knit/pattern.hpp"
#include "util/point_grid.hpp"

namespace knit {
namespace {

struct EndRef {
    uint32_t curve;
    bool atEnd;       // false: first point, true: last point
    uint32_t vertex;  // index in the concatenated vertex list
    glm::dvec2 step;  // the curve's last step leaving through this end (zero for 1-point curves)
};

std::string endName(const EndRef& e) {
    return "curve " + std::to_string(e.curve) + (e.atEnd ? " (last point)" : " (first point)");
}

}  // namespace

Pattern patternFromCurves(const CurveCell& cell, const PartnerOptions& options) {
    if (!(options.tolerance > 0)) throw Error(cell.name + ": partner tolerance must be positive");
    if (!(cell.px > 0 && cell.py > 0 && std::isfinite(cell.px) && std::isfinite(cell.py)))
        throw Error(cell.name + ": period must be positive");
    Pattern p;
    p.name = cell.name;
    p.px = cell.px;
    p.py = cell.py;
    p.radius = cell.radius;

    // 1. Concatenate the curves' points; in-cell edges join consecutive points.
    std::vector<EndRef> ends;
    double longestSegment = 0;
    for (uint32_t c = 0; c < cell.curves.size(); ++c) {
        const auto& curve = cell.curves[c];
        if (curve.empty()) throw Error(cell.name + ": curve " + std::to_string(c) + " has no points");
        const uint32_t first = uint32_t(p.points.size());
        for (size_t i = 0; i < curve.size(); ++i) {
            if (!std::isfinite(curve[i].x) || !std::isfinite(curve[i].y) || !std::isfinite(curve[i].z))
                throw Error(cell.name + ": curve " + std::to_string(c) + " point " + std::to_string(i) +
                            " is not finite");
            p.points.push_back(curve[i]);
            p.twist.push_back(0.0);
            if (i > 0) {
                p.edges.push_back({first + uint32_t(i) - 1, first + uint32_t(i), 0, 0});
                longestSegment =
                    std::max(longestSegment, glm::distance(glm::dvec2(curve[i]), glm::dvec2(curve[i - 1])));
            }
        }
        const size_t last = curve.size() - 1;
        const glm::dvec2 stepOut0 = last ? glm::dvec2(curve[0] - curve[1]) : glm::dvec2(0.0);
        const glm::dvec2 stepOut1 = last ? glm::dvec2(curve[last] - curve[last - 1]) : glm::dvec2(0.0);
        ends.push_back({c, false, first, stepOut0});
        ends.push_back({c, true, first + uint32_t(last), stepOut1});
    }

    // 2. Candidate pairs: end a with end b translated into one of the four neighbouring cells,
    //    within the tolerance (it scales with the longest in-cell segment: a removed periodic
    //    edge is about as long as its neighbours). Pairs are ranked by how well each curve's
    //    last step, continued, lands on the other end: plain distance alone pairs the wrong
    //    ends in real patterns whose periodic edges are as long as their in-cell segments.
    const double tol = options.tolerance * std::max(longestSegment, cell.radius);
    struct Candidate {
        double cost;
        uint32_t a, b;
        int dx, dy;
    };
    //    The ends near each shifted end come from a grid of cell size tol (sub-quadratic on big
    //    curves cells); candidates keep the order of the all-pairs loop (a, then b, then shift).
    std::vector<Candidate> candidates;
    const int shifts[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    std::vector<glm::dvec3> endPoints;
    endPoints.reserve(ends.size());
    for (const EndRef& e : ends) endPoints.emplace_back(glm::dvec2(p.points[e.vertex]), 0.0);
    // The search radius is bounded by 4 periods (a partner is in a neighbouring cell), so an absurd
    //    tolerance cannot make every pair a candidate.
    const double radius = std::min(tol, 4.0 * std::max(cell.px, cell.py));
    const impl::PointGrid grid(std::move(endPoints), radius > 0 ? radius : 1.0);
    std::vector<impl::PointGrid::Neighbour> near;
    std::vector<std::pair<uint32_t, int>> found;  // (b, shift)
    //    Ends packed closer than the search radius make every pair a candidate: 40000 curves in a
    //    1 cm cell asked for 6.4e9 candidates (std::bad_alloc after 3 GB). A real cell has a few
    //    per end; past this many the cell is refused naming why, before the list grows.
    const size_t maxCandidates = 64 * ends.size() + 4096;
    for (uint32_t a = 0; a < ends.size(); ++a) {
        const glm::dvec2 pa(p.points[ends[a].vertex]);
        found.clear();
        for (int k = 0; k < 4; ++k) {
            const glm::dvec2 shift(shifts[k][0] * cell.px, shifts[k][1] * cell.py);
            grid.within(glm::dvec3(pa - shift, 0.0), radius, near);
            for (const impl::PointGrid::Neighbour& nb : near)
                if (nb.index != a) found.push_back({nb.index, k});
        }
        std::sort(found.begin(), found.end());
        for (const auto& [b, k] : found) {
            const glm::dvec2 qb =
                glm::dvec2(p.points[ends[b].vertex]) + glm::dvec2(shifts[k][0] * cell.px, shifts[k][1] * cell.py);
            if (glm::distance(pa, qb) > tol) continue;
            const double cost = glm::distance(pa + ends[a].step, qb) + glm::distance(qb + ends[b].step, pa);
            candidates.push_back({cost, a, b, shifts[k][0], shifts[k][1]});
        }
        if (candidates.size() > maxCandidates) {
            std::ostringstream msg;
            msg << cell.name << ": " << cell.curves.size() << " curves whose ends lie so close together that the "
                << "partner search would weigh more than " << maxCandidates << " candidate pairs (" << found.size()
                << " ends within " << tol << " m of " << endName(ends[a])
                << " alone; the search radius follows the longest in-cell segment, " << longestSegment
                << " m): split the curves into shorter segments, or give the cell fewer curves";
            throw Error(msg.str());
        }
    }

    // 3. Best pairs first; each end takes one partner. A pair (a -> b, s) and its mirror
    //    (b -> a, -s) have the same cost, so the result is symmetric by construction.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& x, const Candidate& y) { return x.cost < y.cost; });
    std::vector<int> partner(ends.size(), -1);
    for (const Candidate& c : candidates) {
        if (partner[c.a] >= 0 || partner[c.b] >= 0) continue;
        partner[c.a] = int(c.b);
        partner[c.b] = int(c.a);
        const EndRef& ea = ends[c.a];
        const EndRef& eb = ends[c.b];
        // Orient the periodic edge along the curves where possible: from a curve's last point
        // to the next curve's first point.
        if (!ea.atEnd && eb.atEnd) p.edges.push_back({eb.vertex, ea.vertex, -c.dx, -c.dy});
        else p.edges.push_back({ea.vertex, eb.vertex, c.dx, c.dy});
    }
    for (uint32_t a = 0; a < ends.size(); ++a) {
        if (partner[a] >= 0) continue;
        std::ostringstream msg;
        msg << cell.name << ": " << endName(ends[a]) << " at (" << p.points[ends[a].vertex].x << ", "
            << p.points[ends[a].vertex].y << ") has no partner endpoint within " << tol << " m in a neighbouring cell";
        throw Error(msg.str());
    }
    validatePattern(p, cell.name);
    return p;
}

CurveCell splitAtPeriodicEdges(const Pattern& pattern, std::vector<uint32_t>* originalVertex) {
    CurveCell cell;
    cell.name = pattern.name;
    cell.px = pattern.px;
    cell.py = pattern.py;
    cell.radius = pattern.radius;
    if (originalVertex) originalVertex->clear();

    // In-cell adjacency only (periodic edges removed).
    std::vector<std::array<int32_t, 2>> nb(pattern.points.size(), {-1, -1});
    auto link = [&](uint32_t a, uint32_t b) {
        auto& s = nb[a];
        if (s[0] < 0) s[0] = int32_t(b);
        else if (s[1] < 0) s[1] = int32_t(b);
        else throw Error(pattern.name + ": vertex " + std::to_string(a) + " has more than two edges");
    };
    for (const PeriodicEdge& e : pattern.edges)
        if (e.dx == 0 && e.dy == 0) {
            link(e.v0, e.v1);
            link(e.v1, e.v0);
        }
    // Walk each in-cell chain from its lowest-numbered end.
    std::vector<uint8_t> seen(pattern.points.size(), 0);
    for (uint32_t start = 0; start < pattern.points.size(); ++start) {
        if (seen[start] || (nb[start][0] >= 0 && nb[start][1] >= 0)) continue;
        std::vector<glm::dvec3> curve;
        int32_t prev = -1, cur = int32_t(start);
        while (cur >= 0) {
            seen[cur] = 1;
            curve.push_back(pattern.points[cur]);
            if (originalVertex) originalVertex->push_back(uint32_t(cur));
            int32_t next = nb[cur][0] != prev ? nb[cur][0] : nb[cur][1];
            if (next >= 0 && seen[next]) next = -1;
            prev = cur;
            cur = next;
        }
        cell.curves.push_back(std::move(curve));
    }
    for (uint32_t v = 0; v < pattern.points.size(); ++v)
        if (!seen[v])
            throw Error(pattern.name + ": vertex " + std::to_string(v) +
                        " lies on a loop with no periodic edge; the curves-only form cannot represent it");
    return cell;
}

}  // namespace knit
