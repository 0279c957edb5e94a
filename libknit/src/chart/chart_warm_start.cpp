// A relaxed chart cell carried to a finer sampling of the same chart (chart_warm_start.hpp).
#include "chart_warm_start.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

namespace knit::warmstart {
namespace {

// One yarn in order: its vertices, the tile each lies in when the yarn is walked from its first
// vertex in tile (0, 0), and for a closed yarn the tile it comes back to its first vertex in.
struct YarnWalk {
    std::vector<uint32_t> vertices;
    std::vector<std::array<int, 2>> tiles;
    bool closed = false;
    std::array<int, 2> round{0, 0};
};

// The yarns of a pattern, ordered by their lowest vertex; an open yarn walked from its free
// start, a closed one from its lowest vertex.
std::vector<YarnWalk> walkYarns(const Pattern& p) {
    const size_t n = p.points.size();
    std::vector<int64_t> out(n, -1), in(n, -1);
    for (size_t k = 0; k < p.edges.size(); ++k) {
        out[p.edges[k].v0] = int64_t(k);
        in[p.edges[k].v1] = int64_t(k);
    }
    std::vector<bool> seen(n, false);
    std::vector<YarnWalk> yarns;
    for (size_t v0 = 0; v0 < n; ++v0) {
        if (seen[v0]) continue;
        // Step 1: the start (walking back to a free end, or round to v0).
        size_t start = v0;
        for (size_t guard = 0; in[start] >= 0 && guard < n; ++guard) {
            const size_t back = p.edges[size_t(in[start])].v0;
            if (back == v0) break;
            start = back;
        }
        // Step 2: forwards, to the free end or round to the start.
        YarnWalk y;
        std::array<int, 2> tile{0, 0};
        size_t v = start;
        while (true) {
            seen[v] = true;
            y.vertices.push_back(uint32_t(v));
            y.tiles.push_back(tile);
            if (out[v] < 0) break;
            const PeriodicEdge& e = p.edges[size_t(out[v])];
            tile = {tile[0] + e.dx, tile[1] + e.dy};
            if (e.v1 == start) {
                y.closed = true;
                y.round = tile;
                break;
            }
            v = e.v1;
        }
        yarns.push_back(std::move(y));
    }
    return yarns;
}

// The yarn's points unwrapped (each in its walk's tile; a closed yarn's first point again at
// the end, in the tile it comes round to) for the period (px, py).
std::vector<glm::dvec3> unwrapped(const YarnWalk& y, const std::vector<glm::dvec3>& points, double px, double py) {
    std::vector<glm::dvec3> u;
    u.reserve(y.vertices.size() + 1);
    for (size_t k = 0; k < y.vertices.size(); ++k)
        u.push_back(points[y.vertices[k]] + glm::dvec3(y.tiles[k][0] * px, y.tiles[k][1] * py, 0));
    if (y.closed) u.push_back(points[y.vertices[0]] + glm::dvec3(y.round[0] * px, y.round[1] * py, 0));
    return u;
}

// Cumulative arc length along a polyline, as a fraction of its length.
std::vector<double> fractions(const std::vector<glm::dvec3>& u) {
    std::vector<double> s(u.size(), 0.0);
    for (size_t k = 1; k < u.size(); ++k) s[k] = s[k - 1] + glm::length(u[k] - u[k - 1]);
    const double total = s.back() > 0 ? s.back() : 1.0;
    for (double& x : s) x /= total;
    return s;
}

// The point at fraction f along polyline `at` whose cumulative fractions are `s`.
struct Place {
    size_t k = 0;  // between vertex k and k + 1
    double a = 0;  // from k towards k + 1
};
Place placeOf(const std::vector<double>& s, double f) {
    if (s.size() < 2) return {};
    const size_t k = size_t(std::clamp<std::ptrdiff_t>(std::upper_bound(s.begin(), s.end(), f) - s.begin() - 1, 0,
                                                       std::ptrdiff_t(s.size()) - 2));
    const double span = s[k + 1] - s[k];
    return {k, span > 0 ? std::clamp((f - s[k]) / span, 0.0, 1.0) : 0.0};
}
glm::dvec3 pointAt(const std::vector<glm::dvec3>& u, const Place& p) {
    return u.size() < 2 ? u.front() : u[p.k] + p.a * (u[p.k + 1] - u[p.k]);
}

// The fine yarn's arc-length fraction at each coarse vertex: where it lies on the fine polyline
// (the closest point on the fine segments within kSearch of its own fraction's place; both
// samplings follow one curve, the fine one closely). The two fractions drift apart by up to a
// coarse segment, as the coarse chords cut the curves short where they bend; projecting the other
// way, several fine vertices beside a coarse corner would fall on the corner itself. Made
// non-decreasing, with the ends fixed.
constexpr size_t kSearch = 8;
std::vector<double> coarseOnFine(const std::vector<glm::dvec3>& coarse, const std::vector<double>& sc,
                                 const std::vector<glm::dvec3>& fine, const std::vector<double>& sf) {
    std::vector<double> at(coarse.size(), 0.0);
    for (size_t i = 0; i < coarse.size(); ++i) {
        const Place guess = placeOf(sf, sc[i]);
        double best = std::numeric_limits<double>::infinity();
        const size_t first = guess.k > kSearch ? guess.k - kSearch : 0;
        const size_t last = fine.size() < 2 ? 0 : std::min(guess.k + kSearch, fine.size() - 2);
        for (size_t k = first; k <= last && fine.size() >= 2; ++k) {
            const glm::dvec3 d = fine[k + 1] - fine[k];
            const double len2 = glm::dot(d, d);
            const double a = len2 > 0 ? std::clamp(glm::dot(coarse[i] - fine[k], d) / len2, 0.0, 1.0) : 0.0;
            const double distance = glm::length(fine[k] + a * d - coarse[i]);
            if (distance < best) best = distance, at[i] = sf[k] + a * (sf[k + 1] - sf[k]);
        }
        if (i > 0) at[i] = std::max(at[i], at[i - 1]);
    }
    at.front() = 0;
    if (at.size() > 1) at.back() = std::max(at.back(), sc.back());  // a closed yarn's end: 1
    return at;
}

// Do two cells' yarns correspond (count, open or closed, the periods a closed yarn goes round)?
bool correspond(const std::vector<YarnWalk>& a, const std::vector<YarnWalk>& b) {
    if (a.size() != b.size()) return false;
    for (size_t y = 0; y < a.size(); ++y)
        if (a[y].closed != b[y].closed || a[y].round != b[y].round) return false;
    return true;
}

}  // namespace

std::optional<FineStart> carryRelaxed(const Pattern& coarseInitial, const Pattern& coarseRelaxed,
                                      const Pattern& fineInitial) {
    const std::vector<YarnWalk> coarse = walkYarns(coarseInitial), fine = walkYarns(fineInitial);
    if (!correspond(coarse, fine) || coarseRelaxed.points.size() != coarseInitial.points.size()) return std::nullopt;
    FineStart out;
    out.points.resize(fineInitial.points.size());
    out.px = coarseRelaxed.px;
    out.py = coarseRelaxed.py;
    for (size_t y = 0; y < fine.size(); ++y) {
        const YarnWalk &c = coarse[y], &f = fine[y];
        const std::vector<glm::dvec3> cInit = unwrapped(c, coarseInitial.points, coarseInitial.px, coarseInitial.py);
        const std::vector<glm::dvec3> cRest = unwrapped(c, coarseRelaxed.points, coarseRelaxed.px, coarseRelaxed.py);
        const std::vector<glm::dvec3> fInit = unwrapped(f, fineInitial.points, fineInitial.px, fineInitial.py);
        const std::vector<double> sf = fractions(fInit), sc = coarseOnFine(cInit, fractions(cInit), fInit, sf);
        for (size_t j = 0; j < f.vertices.size(); ++j) {
            const Place at = placeOf(sc, sf[j]);
            const glm::dvec3 tile(f.tiles[j][0], f.tiles[j][1], 0);
            const uint32_t v = f.vertices[j];
            out.points[v] = pointAt(cRest, at) - tile * glm::dvec3(out.px, out.py, 0);
            const glm::dvec3 back = pointAt(cInit, at) - tile * glm::dvec3(coarseInitial.px, coarseInitial.py, 0);
            out.mismatch = std::max(out.mismatch, glm::length(back - fineInitial.points[v]) / fineInitial.radius);
        }
    }
    return out;
}

}  // namespace knit::warmstart
