// splitByLevel: the mapped yarns cut into pieces per cell level, sharing end points where the
// level changes (knit/detail.hpp).
#include <algorithm>
#include <string>

#include <glm/geometric.hpp>

#include "knit/detail.hpp"
#include "knit/error.hpp"

namespace knit {
namespace {

// Step 1: the level of every yarn vertex, from the UV cell its binding point lies in. A vertex
// in no covered cell (clamped onto the UV boundary) takes its predecessor's level (or the first
// known one of its yarn).
std::vector<DetailLevel> vertexLevels(const Binding& b, const BaseMesh& mesh, const UvGrid& grid,
                                      const CellLevels& levels, std::vector<glm::dvec2>& uv) {
    const size_t n = b.vertexCount();
    std::vector<DetailLevel> out(n, DetailLevel::Culled);
    std::vector<uint8_t> known(n, 0);
    uv.resize(n);
    for (size_t v = 0; v < n; ++v) {
        const SurfacePoint p{b.face[v], glm::dvec3(1.0 - b.bary[v].x - b.bary[v].y, b.bary[v].x, b.bary[v].y)};
        uv[v] = p.interpolate(mesh.uvs, mesh.faceUvs);
        const int32_t slot = grid.slotOf(grid.cellOf(uv[v]));
        if (slot >= 0) out[v] = levels.level[size_t(slot)], known[v] = 1;
    }
    for (size_t y = 0; y < b.yarnCount(); ++y) {
        const uint32_t first = b.offsets[y], last = b.offsets[y + 1];
        const auto firstKnown = std::find(known.begin() + first, known.begin() + last, 1);
        DetailLevel carry = firstKnown == known.begin() + last ? DetailLevel::Culled : out[firstKnown - known.begin()];
        for (uint32_t v = first; v < last; ++v) known[v] ? carry = out[v] : out[v] = carry;
    }
    return out;
}

// Where the UV segment a -> b leaves the grid cell containing a, as a parameter in [0, 1].
double cellExit(const UvGrid& grid, glm::dvec2 a, glm::dvec2 b) {
    const glm::ivec2 c = grid.cellOf(a);
    const glm::dvec2 lo = glm::dvec2(c) * grid.cellSize, hi = lo + grid.cellSize, d = b - a;
    double t = 1.0;
    for (int k = 0; k < 2; ++k) {
        if (d[k] > 0) t = std::min(t, (hi[k] - a[k]) / d[k]);
        if (d[k] < 0) t = std::min(t, (lo[k] - a[k]) / d[k]);
    }
    return std::clamp(t, 0.0, 1.0);
}

struct PieceWriter {
    LevelPieces& out;
    void add(DetailLevel level, const YarnSpan& span, const std::vector<glm::dvec3>& pts,
             const std::vector<glm::dvec3>& nrm, bool closed) {
        const uint32_t yarn = span.yarn;
        if (level != DetailLevel::Plies && level != DetailLevel::Yarns) return;
        // A yarn that only touches a cell (its last vertex on the cell's edge) leaves a piece of
        // length zero there: nothing to draw.
        if (std::all_of(pts.begin(), pts.end(), [&](const glm::dvec3& p) { return p == pts[0]; })) return;
        MappedYarns& m = level == DetailLevel::Plies ? out.plies : out.yarns;
        m.curves.addCurve(pts.data(), pts.size(), closed);
        m.normals.insert(m.normals.end(), nrm.begin(), nrm.end());
        (level == DetailLevel::Plies ? out.plyPieceYarn : out.yarnPieceYarn).push_back(yarn);
        (level == DetailLevel::Plies ? out.plySpans : out.yarnSpans).push_back(span);
    }
};

// The point where the yarn leaves the cell of vertex v on its way to w, and its normal; returns
// its fraction of the way from v to w.
double exitPoint(const MappedYarns& yarns, const std::vector<glm::dvec2>& uv, const UvGrid& grid, uint32_t v,
                 uint32_t w, glm::dvec3& p, glm::dvec3& q) {
    const double t = cellExit(grid, uv[v], uv[w]);
    const std::vector<glm::dvec3>& x = yarns.curves.points;
    p = x[v] + t * (x[w] - x[v]);
    q = glm::normalize(yarns.normals[v] + t * (yarns.normals[w] - yarns.normals[v]));
    return t;
}

// Step 2: one yarn cut into runs of one level; consecutive runs share the point where the yarn
// leaves the last cell of the first run. A cut loop starts right after a level change.
void splitYarn(const MappedYarns& yarns, uint32_t y, const std::vector<DetailLevel>& level,
               const std::vector<glm::dvec2>& uv, const UvGrid& grid, PieceWriter& writer) {
    const Polylines& c = yarns.curves;
    const uint32_t b = c.begin(y), n = c.size(y);
    const bool closed = c.isClosed(y);
    const bool uniform =
        std::all_of(level.begin() + b, level.begin() + b + n, [&](DetailLevel l) { return l == level[b]; });
    uint32_t start = 0;
    std::vector<glm::dvec3> pts, nrm;
    // The span of the run being collected, in vertex units. Unwrapped: vertex start + s sits at
    // base + start + s, with base = n when the first run begins on the closing segment (start 0).
    YarnSpan span{y, 0.0, 0.0, false};
    double base = 0.0;
    if (closed && !uniform) {
        while (level[b + start] == level[b + (start + n - 1) % n]) ++start;
        if (start == 0) base = double(n);
        pts.resize(1), nrm.resize(1);
        span.begin =
            base + double(start) - 1.0 + exitPoint(yarns, uv, grid, b + (start + n - 1) % n, b + start, pts[0], nrm[0]);
    }
    for (uint32_t s = 0; s < n; ++s) {
        const uint32_t v = b + (start + s) % n, w = b + (start + s + 1) % n;
        pts.push_back(c.points[v]), nrm.push_back(yarns.normals[v]);
        const double at = base + double(start + s);  // unwrapped vertex position of v
        if (!closed && s + 1 == n) {
            span.end = at;
            writer.add(level[v], span, pts, nrm, false);
        } else if (level[w] == level[v]) {
            if (s + 1 == n) writer.add(level[v], YarnSpan{y, 0.0, double(n), true}, pts, nrm, true);  // a whole loop
        } else {
            glm::dvec3 p, q;
            span.end = at + exitPoint(yarns, uv, grid, v, w, p, q);
            pts.push_back(p), nrm.push_back(q);
            writer.add(level[v], span, pts, nrm, false);
            span.begin = span.end;
            pts.assign(1, p), nrm.assign(1, q);
        }
    }
}

}  // namespace

LevelPieces splitByLevel(const MappedYarns& yarns, const Binding& binding, const BaseMesh& mesh, const UvGrid& grid,
                         const CellLevels& levels) {
    if (binding.offsets != yarns.curves.offsets || yarns.normals.size() != yarns.curves.pointCount())
        throw Error("cannot build the view: the yarns are not the evaluation of the binding (vertex counts differ)");
    if (levels.level.size() != grid.cells.size())
        throw Error("cannot build the view: the cell levels are not those of the grid (" +
                    std::to_string(levels.level.size()) + " levels for " + std::to_string(grid.cells.size()) +
                    " cells)");
    LevelPieces out;
    std::vector<glm::dvec2> uv;
    const std::vector<DetailLevel> level = vertexLevels(binding, mesh, grid, levels, uv);
    PieceWriter writer{out};
    for (uint32_t y = 0; y < yarns.curves.curveCount(); ++y) splitYarn(yarns, y, level, uv, grid, writer);
    // Step 3: the base-mesh triangles of surface cells.
    for (size_t k = 0; k < grid.cells.size(); ++k)
        if (levels.level[k] == DetailLevel::Surface)
            out.surfaceFaces.insert(out.surfaceFaces.end(), grid.triangles.begin() + grid.triOffsets[k],
                                    grid.triangles.begin() + grid.triOffsets[k + 1]);
    std::sort(out.surfaceFaces.begin(), out.surfaceFaces.end());
    out.surfaceFaces.erase(std::unique(out.surfaceFaces.begin(), out.surfaceFaces.end()), out.surfaceFaces.end());
    return out;
}

}  // namespace knit
