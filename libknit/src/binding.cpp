// Binding: locate yarn vertices on the base mesh, cut yarns where they leave the UV region,
// weld ends that meet again across seams, and evaluate the binding on any pose.
#include "knit/binding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "knit/error.hpp"
#include "knit/stitch.hpp"

namespace knit {
namespace {

struct BoundVertex {
    uint32_t face;
    glm::dvec3 bary;
    double height, twist;
};

// A maximal run of located vertices of one yarn (yarn-local indices start, start+1, ... modulo
// the yarn's size), with boundary-crossing vertices before (head) and after (tail) it.
struct Piece {
    uint32_t yarnBegin = 0, yarnSize = 0, start = 0, count = 0;
    std::optional<BoundVertex> head, tail;
    bool closed = false;
    bool boundaryEnd[2] = {false, false};  // [0] first point, [1] last point lies on a UV boundary

    size_t size() const { return count + (head ? 1 : 0) + (tail ? 1 : 0); }
};

glm::dvec3 evaluatePoint(const BaseMesh& mesh, const std::vector<glm::dvec3>& normals, const BoundVertex& b) {
    const glm::uvec3 f = mesh.faces[b.face];
    const glm::dvec3 p = b.bary.x * mesh.positions[f.x] + b.bary.y * mesh.positions[f.y] + b.bary.z * mesh.positions[f.z];
    const glm::dvec3 n = b.bary.x * normals[f.x] + b.bary.y * normals[f.y] + b.bary.z * normals[f.z];
    const double len = glm::length(n);
    return len > 0 ? p + (b.height / len) * n : p;
}

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

// Calls visit(halfEdge, t, s) for every boundary edge of `chart` that the UV segment p -> q
// crosses or touches (t along p -> q, s along the edge; both within [-slack, 1 + slack]),
// looking only at the cells in [c0, c1]. Parallel edges are skipped: running along the
// boundary stays in the chart.
template <class Visit>
void forEachBoundaryCrossing(const BaseMesh& mesh, const UvGrid& grid, uint32_t chart, glm::dvec2 p, glm::dvec2 q,
                             glm::ivec2 c0, glm::ivec2 c1, double slack, Visit visit) {
    const glm::dvec2 d = q - p;
    for (int32_t y = c0.y; y <= c1.y; ++y)
        for (int32_t x = c0.x; x <= c1.x; ++x) {
            const int32_t slot = grid.slotOf({x, y});
            if (slot < 0) continue;
            for (uint32_t i = grid.edgeOffsets[slot]; i < grid.edgeOffsets[slot + 1]; ++i) {
                const uint32_t he = grid.boundaryEdges[i], f = he / 3, k = he % 3;
                if (grid.chartOfFace[f] != chart) continue;
                const glm::uvec3 t = mesh.faceUvs[f];
                const uint32_t corner[3] = {t.x, t.y, t.z};
                const glm::dvec2 a = mesh.uvs[corner[k]], e = mesh.uvs[corner[(k + 1) % 3]] - a;
                const double den = cross2(d, e);
                if (den == 0) continue;
                const double tt = cross2(a - p, e) / den, s = cross2(a - p, d) / den;
                if (tt < -slack || tt > 1 + slack || s < -slack || s > 1 + slack) continue;
                visit(he, tt, s);
            }
        }
}

// First crossing of the UV segment p -> q with a boundary edge of `chart`, as a bound vertex
// with height and twist interpolated along the segment. None when p is already on the boundary
// (t ~ 0) or no boundary edge is crossed.
std::optional<BoundVertex> boundaryCrossing(const BaseMesh& mesh, const UvGrid& grid, uint32_t chart,
                                            glm::dvec2 p, glm::dvec2 q, double hp, double hq, double tp, double tq) {
    double bestT = INFINITY;
    uint32_t bestEdge = UINT32_MAX;
    double bestS = 0;
    forEachBoundaryCrossing(mesh, grid, chart, p, q, grid.cellOf(glm::min(p, q)), grid.cellOf(glm::max(p, q)), 1e-12,
                            [&](uint32_t he, double tt, double s) {
                                if (tt < bestT || (tt == bestT && he < bestEdge)) {
                                    bestT = std::clamp(tt, 0.0, 1.0);
                                    bestEdge = he;
                                    bestS = std::clamp(s, 0.0, 1.0);
                                }
                            });
    if (bestEdge == UINT32_MAX || bestT < 1e-9) return std::nullopt;
    BoundVertex b;
    b.face = bestEdge / 3;
    b.bary = glm::dvec3(0.0);
    b.bary[bestEdge % 3] = 1.0 - bestS;
    b.bary[(bestEdge % 3 + 1) % 3] = bestS;
    b.height = hp + bestT * (hq - hp);
    b.twist = tp + bestT * (tq - tp);
    return b;
}

// True when p lies in a (closed) UV triangle of `chart` listed in p's cell (double precision
// with a relative tolerance: it decides only the middle of a segment piece, see leavesChart).
bool insideChart(const BaseMesh& mesh, const UvGrid& grid, uint32_t chart, glm::dvec2 p) {
    const int32_t slot = grid.slotOf(grid.cellOf(p));
    if (slot < 0) return false;
    for (uint32_t i = grid.triOffsets[slot]; i < grid.triOffsets[slot + 1]; ++i) {
        const uint32_t f = grid.triangles[i];
        if (grid.chartOfFace[f] != chart) continue;
        const glm::uvec3 t = mesh.faceUvs[f];
        const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
        const double den = cross2(b - a, c - a);
        const double l1 = cross2(p - a, c - a) / den, l2 = cross2(b - a, p - a) / den, l0 = 1.0 - l1 - l2;
        const double eps = -1e-12;
        if (l0 >= eps && l1 >= eps && l2 >= eps) return true;
    }
    return false;
}

// True when the UV segment p -> q between two vertices located in `chart` passes outside the
// chart on the way: over a gap, a hole or a notch of the UV layout narrower than the segment,
// where the surface is not continuous (the segment would be a chord through the air in 3D).
// The chart's boundary edges crossed by the segment split it into pieces; a piece whose middle
// lies in no triangle of the chart is outside. Pieces within `tol` of an end are ignored: a
// clamped end lies up to `tol` outside. Cells without boundary edges cost one lookup each.
// cp, cq: the grid cells of p and q.
bool leavesChart(const BaseMesh& mesh, const UvGrid& grid, uint32_t chart, glm::dvec2 p, glm::dvec2 q, glm::ivec2 cp,
                 glm::ivec2 cq, double tol, std::vector<double>& ts) {
    const glm::ivec2 c0 = glm::min(cp, cq), c1 = glm::max(cp, cq);  // cellOf is monotone
    if (c0 == c1) {  // fast path: a step inside one cell without boundary edges
        const int32_t slot = grid.slotOf(c0);
        if (slot < 0 || grid.edgeOffsets[slot] == grid.edgeOffsets[slot + 1]) return false;
    }
    const glm::dvec2 d = q - p;
    ts.clear();
    forEachBoundaryCrossing(mesh, grid, chart, p, q, c0, c1, 0.0, [&](uint32_t, double tt, double) {
        if (tt > 0 && tt < 1) ts.push_back(tt);
    });
    if (ts.empty()) return false;
    std::sort(ts.begin(), ts.end());
    ts.push_back(1.0);
    const double len = glm::length(d);
    double prev = 0.0;
    for (const double t : ts) {
        const double mid = 0.5 * (prev + t);
        const bool nearEnd = mid * len <= tol || (1.0 - mid) * len <= tol;
        if (t > prev && !nearEnd && !insideChart(mesh, grid, chart, p + mid * d)) return true;
        prev = t;
    }
    return false;
}

}  // namespace

BindResult bindYarns(const BaseMesh& mesh, const std::vector<glm::dvec3>& normals, const UvGrid& grid,
                     const UvYarns& yarns, const BindOptions& options) {
    if (!(options.yarnRadius > 0) || !(options.clampTolerance >= 0) || !(options.weldTolerance >= 0) ||
        !std::isfinite(options.yarnRadius) || !std::isfinite(options.clampTolerance) || !std::isfinite(options.weldTolerance))
        throw Error("binding: yarn radius must be positive, clamp and weld tolerances non-negative");
    if (normals.size() != mesh.positions.size()) throw Error("binding: normals do not match the mesh's vertices");
    if (yarns.offsets.size() != yarns.yarnCount() + 1 || yarns.offsets.front() != 0 ||
        yarns.offsets.back() != yarns.vertexCount() || !std::is_sorted(yarns.offsets.begin(), yarns.offsets.end()) ||
        yarns.height.size() != yarns.vertexCount() || yarns.twist.size() != yarns.vertexCount() ||
        (!yarns.ghosts.empty() && yarns.ghosts.size() != yarns.yarnCount()) ||
        (!yarns.chart.empty() && yarns.chart.size() != yarns.yarnCount()))
        throw Error("binding: inconsistent UvYarns (offsets, heights, twists, ghosts or charts do not match the vertices)");
    BindResult result;
    BindStats& stats = result.stats;
    const size_t nv = yarns.vertexCount();

    // 1. Locate every yarn vertex: yarns in parallel, each walked in order with the previous
    //    vertex's triangle as the hint (deterministic for any thread count).
    const glm::dvec2 metresPerUv = uvToMetreScale(mesh);
    const double radiusUv = options.yarnRadius / std::max(metresPerUv.x, metresPerUv.y);
    const double tolUv = options.clampTolerance * radiusUv;
    //    Then, per step i -> i+1 (last -> first on closed yarns) between two vertices of one
    //    chart: whether the step leaves the chart (leavesChart), for step 2.
    // `loc` is left uninitialized (every entry is constructed below, in parallel): a serial
    // value-initialization of ~48 bytes per vertex would cost as much as half the locating.
    static_assert(std::is_trivially_destructible_v<LocateResult>, "loc is freed without destructors");
    struct Free {
        void operator()(LocateResult* p) const { std::free(p); }
    };
    const std::unique_ptr<LocateResult[], Free> locStorage(
        static_cast<LocateResult*>(std::malloc(std::max<size_t>(nv, 1) * sizeof(LocateResult))));
    if (!locStorage) throw std::bad_alloc();
    LocateResult* const loc = locStorage.get();
    std::vector<uint8_t> leaves(nv, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarns.yarnCount(), 1), [&](const tbb::blocked_range<size_t>& r) {
        std::vector<double> crossings;  // scratch for leavesChart
        for (size_t y = r.begin(); y != r.end(); ++y) {
            const size_t b = yarns.offsets[y], e = yarns.offsets[y + 1];
            const uint32_t only = yarns.chart.empty() ? kAnyChart : yarns.chart[y];
            uint32_t hint = UINT32_MAX;
            for (size_t i = b; i < e; ++i) {
                LocateResult r = locatePoint(mesh, grid, yarns.uv[i], tolUv, hint, only);
                // A yarn tiled for one chart is not clamped onto it from inside another chart:
                // that point belongs to the other chart's own yarns.
                if (r.status == LocateStatus::Clamped && only != kAnyChart) {
                    const LocateResult any = locatePoint(mesh, grid, yarns.uv[i], 0.0);
                    if (any.status == LocateStatus::Inside && grid.chartOfFace[any.point.face] != only) r = LocateResult{};
                }
                new (loc + i) LocateResult(r);
                hint = loc[i].status == LocateStatus::Inside ? loc[i].point.face : UINT32_MAX;
            }
            for (size_t i = b; i < e; ++i) {
                const size_t j = i + 1 < e ? i + 1 : b;
                if ((j == b && !yarns.closed[y]) || loc[i].status == LocateStatus::Outside ||
                    loc[j].status == LocateStatus::Outside)
                    continue;
                // Both inside one (convex) triangle: the step cannot leave it.
                if (loc[i].point.face == loc[j].point.face && loc[i].status == LocateStatus::Inside &&
                    loc[j].status == LocateStatus::Inside)
                    continue;
                const uint32_t c = grid.chartOfFace[loc[i].point.face];
                if (c == grid.chartOfFace[loc[j].point.face])
                    leaves[i] = leavesChart(mesh, grid, c, yarns.uv[i], yarns.uv[j], grid.cellOf(yarns.uv[i]),
                                            grid.cellOf(yarns.uv[j]), tolUv, crossings);
            }
        }
    });
    auto located = [&](size_t i) { return loc[i].status != LocateStatus::Outside; };
    auto chart = [&](size_t i) { return grid.chartOfFace[loc[i].point.face]; };
    auto bound = [&](size_t i) {
        return BoundVertex{loc[i].point.face, loc[i].point.bary, yarns.height[i], yarns.twist[i]};
    };
    // Vertex k of a piece, in piece order.
    auto at = [&](const Piece& pc, size_t k) {
        if (pc.head) {
            if (k == 0) return *pc.head;
            --k;
        }
        if (k == pc.count) return *pc.tail;
        return bound(pc.yarnBegin + (pc.start + k) % pc.yarnSize);
    };
    for (size_t i = 0; i < nv; ++i) {
        if (loc[i].status == LocateStatus::Clamped) ++stats.clampedVertices;
        if (!located(i)) ++stats.cutVertices;
    }

    // 2. Split each yarn into pieces at unlocated vertices, at chart changes and where a step
    //    leaves its chart (leavesChart); cut ends get a vertex where the yarn crosses the UV
    //    boundary.
    std::vector<Piece> pieces;
    for (size_t y = 0; y < yarns.yarnCount(); ++y) {
        const size_t b = yarns.offsets[y], n = yarns.offsets[y + 1] - b;
        if (n == 0) continue;
        const bool closed = yarns.closed[y] != 0;
        // Consecutive vertices i -> j = i+1 stay joined when both are located in the same chart
        // and the step between them does not leave the chart.
        auto joined = [&](size_t i, size_t j) {
            return located(b + i) && located(b + j) && chart(b + i) == chart(b + j) && !leaves[b + i];
        };
        size_t breakAt = 0;  // a run boundary to start from (closed yarns)
        if (closed) {
            bool anyBreak = false;
            for (size_t i = 0; i < n && !anyBreak; ++i)
                if (!joined((i + n - 1) % n, i)) {
                    breakAt = i;
                    anyBreak = true;
                }
            if (!anyBreak) {
                Piece piece;
                piece.yarnBegin = uint32_t(b);
                piece.yarnSize = piece.count = uint32_t(n);
                piece.closed = true;
                pieces.push_back(piece);
                continue;
            }
        }
        // Crossing from located vertex i towards a cut neighbour (a yarn vertex or a ghost).
        auto crossingTowards = [&](size_t i, const GhostVertex& target) {
            const size_t p = b + i;
            auto x = boundaryCrossing(mesh, grid, chart(p), yarns.uv[p], target.uv, yarns.height[p], target.height,
                                      yarns.twist[p], target.twist);
            if (x) ++stats.boundaryVertices;
            return x;
        };
        auto vertexAsTarget = [&](size_t i) {
            return GhostVertex{true, yarns.uv[b + i], yarns.height[b + i], yarns.twist[b + i]};
        };
        const GhostVertex noGhost;
        const GhostVertex& startGhost = closed || yarns.ghosts.empty() ? noGhost : yarns.ghosts[y][0];
        const GhostVertex& endGhost = closed || yarns.ghosts.empty() ? noGhost : yarns.ghosts[y][1];
        Piece cur;
        auto finish = [&](size_t lastIdx, const GhostVertex& beyond) {
            if (cur.count == 0) return;
            if (beyond.present) {
                cur.tail = crossingTowards(lastIdx, beyond);
                cur.boundaryEnd[1] = true;
            }
            if (cur.size() >= 2) pieces.push_back(cur);
            else ++stats.cutVertices;
            cur = Piece{};
        };
        for (size_t s = 0; s < n; ++s) {
            const size_t i = (breakAt + s) % n;
            const size_t prev = (i + n - 1) % n;
            if (!located(b + i)) {
                finish(prev, vertexAsTarget(i));
                continue;
            }
            if (cur.count > 0 && !joined(prev, i)) finish(prev, vertexAsTarget(i));
            if (cur.count == 0) {
                cur.yarnBegin = uint32_t(b);
                cur.yarnSize = uint32_t(n);
                cur.start = uint32_t(i);
                // Entering from a cut: start with the boundary crossing towards the previous vertex.
                const bool cutBefore = closed || s > 0;
                if (cutBefore || startGhost.present) {
                    cur.head = crossingTowards(i, cutBefore ? vertexAsTarget(prev) : startGhost);
                    cur.boundaryEnd[0] = true;
                }
            }
            ++cur.count;
        }
        // The last run of a closed yarn ends at the break it started from; an open yarn's last
        // run may end at a ghost.
        if (closed) finish((breakAt + n - 1) % n, vertexAsTarget(breakAt));
        else finish(n - 1, endGhost);
    }

    // 3. Weld boundary ends that meet in object space with continuing tangents.
    const double weldTol = options.weldTolerance * options.yarnRadius;
    std::vector<int64_t> partner(2 * pieces.size(), -1);
    if (options.weld && weldTol > 0) {
        struct End {
            glm::dvec3 p, out;  // position, outward unit direction
        };
        std::vector<End> ends(2 * pieces.size());
        std::unordered_map<uint64_t, std::vector<uint32_t>> hash;
        auto key = [&](glm::ivec3 c) {
            return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) | uint64_t(uint32_t(c.z) & 0x1FFFFF);
        };
        auto cellOf = [&](glm::dvec3 p) { return glm::ivec3(glm::floor(p / weldTol)); };
        for (size_t pi = 0; pi < pieces.size(); ++pi) {
            const Piece& pc = pieces[pi];
            if (pc.closed) continue;
            for (int e = 0; e < 2; ++e) {
                if (!pc.boundaryEnd[e]) continue;
                const BoundVertex endV = at(pc, e ? pc.size() - 1 : 0);
                const BoundVertex inner = at(pc, e ? pc.size() - 2 : 1);
                End& end = ends[2 * pi + e];
                end.p = evaluatePoint(mesh, normals, endV);
                const glm::dvec3 dir = end.p - evaluatePoint(mesh, normals, inner);
                const double len = glm::length(dir);
                end.out = len > 0 ? dir / len : glm::dvec3(0.0);
                hash[key(cellOf(end.p))].push_back(uint32_t(2 * pi + e));
            }
        }
        struct Candidate {
            double dist;
            uint32_t a, b;
        };
        std::vector<Candidate> candidates;
        for (const auto& [k, list] : hash)
            for (uint32_t a : list) {
                const glm::ivec3 c = cellOf(ends[a].p);
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            auto it = hash.find(key(c + glm::ivec3(dx, dy, dz)));
                            if (it == hash.end()) continue;
                            for (uint32_t bb : it->second) {
                                if (bb <= a) continue;
                                const double dist = glm::distance(ends[a].p, ends[bb].p);
                                if (dist > weldTol) continue;
                                if (glm::dot(ends[a].out, -ends[bb].out) < options.weldMinCos) continue;
                                candidates.push_back({dist, a, bb});
                            }
                        }
            }
        std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
            return x.dist != y.dist ? x.dist < y.dist : (x.a != y.a ? x.a < y.a : x.b < y.b);
        });
        for (const Candidate& c : candidates) {
            if (partner[c.a] >= 0 || partner[c.b] >= 0) continue;
            partner[c.a] = c.b;
            partner[c.b] = c.a;
            stats.weldedEnds += 2;
        }
    }

    // 4. Chain pieces along welds into yarns; a chain that returns to its start is a loop.
    //    First the plan, piece by piece (serial, cheap): which pieces in which direction, and
    //    whether a junction vertex repeats the previous one (dropped); then every vertex is
    //    copied to its place in parallel.
    struct Segment {
        uint32_t piece;
        bool reversed, dropFirst, dropLast;
        size_t outStart;
    };
    std::vector<Segment> segments;
    segments.reserve(pieces.size());
    Binding& out = result.binding;
    const double dedupe = 1e-4 * options.yarnRadius;
    std::vector<uint8_t> used(pieces.size(), 0);
    size_t outCount = 0;       // vertices planned so far
    size_t yarnFirstSeg = 0;   // first segment of the yarn being planned
    auto emitted = [](const Segment& g, const Piece& pc) {
        return pc.size() - (g.dropFirst ? 1 : 0) - (g.dropLast ? 1 : 0);
    };
    auto endVertex = [&](const Segment& g, bool last) {  // first / last vertex of a segment, piece order applied
        const Piece& pc = pieces[g.piece];
        return at(pc, last != g.reversed ? pc.size() - 1 : 0);
    };
    auto addSegment = [&](size_t pi, bool reversed, bool dropFirst) {
        Segment g{uint32_t(pi), reversed, dropFirst, false, outCount};
        outCount += emitted(g, pieces[pi]);
        segments.push_back(g);
    };
    auto walkChain = [&](size_t first, int enterEnd) {
        size_t pi = first;
        int enter = enterEnd;
        bool firstPiece = true;
        for (;;) {
            used[pi] = 1;
            const Piece& pc = pieces[pi];
            const bool reversed = enter == 1;
            const glm::dvec3 head = evaluatePoint(mesh, normals, at(pc, reversed ? pc.size() - 1 : 0));
            const bool drop =
                !firstPiece && glm::distance(evaluatePoint(mesh, normals, endVertex(segments.back(), true)), head) < dedupe;
            addSegment(pi, reversed, drop);
            firstPiece = false;
            const int64_t next = partner[2 * pi + (1 - enter)];
            if (next < 0) return false;
            pi = size_t(next / 2);
            enter = int(next % 2);
            if (used[pi]) {
                // Back at the start: a closed loop; drop the duplicated closing vertex.
                Segment& lastSeg = segments.back();
                const size_t yarnSize = outCount - segments[yarnFirstSeg].outStart;
                if (yarnSize > 2 && glm::distance(evaluatePoint(mesh, normals, endVertex(lastSeg, true)),
                                                  evaluatePoint(mesh, normals, endVertex(segments[yarnFirstSeg], false))) <
                                        dedupe) {
                    lastSeg.dropLast = true;
                    --outCount;
                }
                return true;
            }
        }
    };
    auto closeYarn = [&](bool closed) {
        out.offsets.push_back(uint32_t(outCount));
        out.closed.push_back(closed ? 1 : 0);
        if (closed) ++stats.closedLoops;
        else stats.openEnds += 2;
        yarnFirstSeg = segments.size();
    };
    for (size_t pi = 0; pi < pieces.size(); ++pi) {
        if (used[pi] || !pieces[pi].closed) continue;
        used[pi] = 1;
        addSegment(pi, false, false);
        closeYarn(true);
    }
    for (size_t pi = 0; pi < pieces.size(); ++pi)
        for (int e = 0; e < 2; ++e)
            if (!used[pi] && partner[2 * pi + e] < 0) closeYarn(walkChain(pi, e));
    for (size_t pi = 0; pi < pieces.size(); ++pi)
        if (!used[pi]) closeYarn(walkChain(pi, 0));

    // Fill: every segment's vertices in parallel.
    tbb::parallel_invoke([&] { out.face.resize(outCount); }, [&] { out.bary.resize(outCount); },
                         [&] { out.height.resize(outCount); }, [&] { out.twist.resize(outCount); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, segments.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
            const Segment& g = segments[k];
            const Piece& pc = pieces[g.piece];
            const size_t n = pc.size();
            size_t o = g.outStart;
            for (size_t s = g.dropFirst ? 1 : 0; s < n - (g.dropLast ? 1 : 0); ++s, ++o) {
                const BoundVertex v = at(pc, g.reversed ? n - 1 - s : s);
                out.face[o] = v.face;
                out.bary[o] = glm::dvec2(v.bary.y, v.bary.z);
                out.height[o] = v.height;
                out.twist[o] = v.twist;
            }
        }
    });
    return result;
}

namespace {

// The evaluation kernel shared by the double and the float32 entry points: a flat gather,
// P = sum b_i x_i + h * normalize(sum b_i n_i), handed to `store(i, P, n)`.
template <class Store>
void evaluateKernel(const Binding& binding, const std::vector<glm::uvec3>& faces, const std::vector<glm::dvec3>& positions,
                    const std::vector<glm::dvec3>& normals, Store store) {
    const size_t n = binding.vertexCount();
    const uint32_t* face = binding.face.data();
    const glm::dvec2* bary = binding.bary.data();
    const double* height = binding.height.data();
    const glm::uvec3* tri = faces.data();
    const glm::dvec3* X = positions.data();
    const glm::dvec3* Nv = normals.data();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const glm::uvec3 f = tri[face[i]];
            const double b1 = bary[i].x, b2 = bary[i].y, b0 = 1.0 - b1 - b2;
            const glm::dvec3 p = b0 * X[f.x] + b1 * X[f.y] + b2 * X[f.z];
            glm::dvec3 nn = b0 * Nv[f.x] + b1 * Nv[f.y] + b2 * Nv[f.z];
            const double len2 = glm::dot(nn, nn);
            nn = len2 > 0 ? nn * (1.0 / std::sqrt(len2)) : glm::dvec3(0.0, 0.0, 1.0);
            store(i, p + height[i] * nn, nn);
        }
    });
}

}  // namespace

void evaluateBinding(const Binding& binding, const std::vector<glm::uvec3>& faces,
                     const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                     MappedYarns& out) {
    const size_t n = binding.vertexCount();
    out.curves.points.resize(n);
    out.curves.offsets = binding.offsets;
    out.curves.closed = binding.closed;
    out.normals.resize(n);
    glm::dvec3* P = out.curves.points.data();
    glm::dvec3* N = out.normals.data();
    evaluateKernel(binding, faces, positions, normals, [P, N](size_t i, const glm::dvec3& p, const glm::dvec3& nn) {
        P[i] = p;
        N[i] = nn;
    });
}

void evaluateBindingFloat(const Binding& binding, const std::vector<glm::uvec3>& faces,
                          const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                          glm::dvec3 origin, std::vector<glm::vec3>& out) {
    out.resize(binding.vertexCount());
    glm::vec3* P = out.data();
    evaluateKernel(binding, faces, positions, normals,
                   [P, origin](size_t i, const glm::dvec3& p, const glm::dvec3&) { P[i] = glm::vec3(p - origin); });
}

}  // namespace knit
