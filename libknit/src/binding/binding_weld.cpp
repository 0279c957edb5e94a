// binding_weld.cpp — binding phase 3: greedy nearest-first welding of cut ends (see
// binding_weld.hpp).
#include "binding_weld.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

#include "util/point_grid.hpp"

namespace knit::impl {
namespace {

struct Candidate {
    double dist;
    uint32_t a, b;  // end ids, a < b
};

// Pairs of present ends within the tolerance whose tangents continue, nearest first.
std::vector<Candidate> weldCandidates(const std::vector<WeldEnd>& ends, const WeldOptions& options) {
    // The present ends in a grid with cells of the tolerance (ascending end ids).
    std::vector<uint32_t> ids;
    std::vector<glm::dvec3> points;
    for (size_t e = 0; e < ends.size(); ++e)
        if (ends[e].present) {
            ids.push_back(uint32_t(e));
            points.push_back(ends[e].position);
        }
    const PointGrid grid(std::move(points), options.tolerance);
    // Each pair once, from its lower end.
    std::vector<Candidate> candidates;
    std::vector<PointGrid::Neighbour> near;
    for (size_t k = 0; k < ids.size(); ++k) {
        grid.within(grid.point(k), options.tolerance, near);
        for (const PointGrid::Neighbour& nb : near) {
            if (nb.index <= k) continue;
            const uint32_t a = ids[k], b = ids[nb.index];
            if (glm::dot(ends[a].outward, -ends[b].outward) < options.minCos) continue;
            candidates.push_back({nb.distance, a, b});
        }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
        return x.dist != y.dist ? x.dist < y.dist : (x.a != y.a ? x.a < y.a : x.b < y.b);
    });
    return candidates;
}

}  // namespace

std::vector<WeldEnd> pieceEnds(const RestSurface& rest, const std::vector<Piece>& pieces,
                               const PieceVertices& vertices) {
    std::vector<WeldEnd> ends(2 * pieces.size());
    for (size_t pi = 0; pi < pieces.size(); ++pi) {
        const Piece& pc = pieces[pi];
        if (pc.closed) continue;
        for (int e = 0; e < 2; ++e) {
            if (!pc.boundaryEnd[e]) continue;
            WeldEnd& end = ends[2 * pi + e];
            end.present = true;
            end.position = rest.position(vertices.end(pc, e == 1));
            const BoundVertex inner = vertices.at(pc, e ? pc.size() - 2 : 1);
            const glm::dvec3 dir = end.position - rest.position(inner);
            const double len = glm::length(dir);
            end.outward = len > 0 ? dir / len : glm::dvec3(0.0);
        }
    }
    return ends;
}

WeldResult weldEnds(const std::vector<WeldEnd>& ends, const WeldOptions& options) {
    WeldResult out;
    out.partner.assign(ends.size(), -1);
    if (!(options.tolerance > 0)) return out;
    // Nearest first; an end already welded is skipped.
    for (const Candidate& c : weldCandidates(ends, options)) {
        if (out.partner[c.a] >= 0 || out.partner[c.b] >= 0) continue;
        out.partner[c.a] = c.b;
        out.partner[c.b] = c.a;
        out.weldedEnds += 2;
    }
    return out;
}

}  // namespace knit::impl
