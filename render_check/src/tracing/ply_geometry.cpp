// Ply segments for the tracer and their UV-grid cells.
#include "knit/ply_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/scene.hpp"
#include "util/math.hpp"

namespace knit {
namespace {
using util::kPi;
}  // namespace

size_t PlyGeometry::intersectionBytes() const {
    return points.size() * sizeof(glm::vec4) + segments.size() * sizeof(uint32_t) + flags.size();
}

size_t PlyGeometry::shadingBytes() const {
    return (radial.size() + colour.size()) * sizeof(glm::vec3) + arc.size() * sizeof(float) +
           curveOfSegment.size() * sizeof(uint32_t);
}

PlyGeometry buildPlyGeometry(const Plies& plies, const glm::dvec3& origin, double fiberTwist) {
    const Polylines& c = plies.curves;
    if (c.curveCount() == 0 || c.pointCount() == 0)
        throw Error("cannot render: the scene has no ply curves (nothing to render)");
    if (!(plies.plyRadius > 0) || !std::isfinite(plies.plyRadius))
        throw Error("cannot render: ply radius must be positive (got " + std::to_string(plies.plyRadius) + ")");
    if (plies.radial.size() != c.pointCount())
        throw Error("cannot render: plies have " + std::to_string(plies.radial.size()) + " radial directions for " +
                    std::to_string(c.pointCount()) + " points");
    if (!plies.colour.empty() && plies.colour.size() != c.pointCount())
        throw Error("cannot render: plies have " + std::to_string(plies.colour.size()) + " colours for " +
                    std::to_string(c.pointCount()) + " points");
    PlyGeometry g;
    g.origin = origin;
    g.unit = plies.plyRadius;
    g.radius = 1.0f;
    const double invR = 1.0 / plies.plyRadius;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        // Step 1: distinct consecutive points of the curve (and their radial directions).
        std::vector<uint32_t> idx;
        for (uint32_t p = c.begin(k); p < c.end(k); ++p) {
            const glm::dvec3& q = c.points[p];
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                throw Error("cannot render: ply curve " + std::to_string(k) + " point " +
                            std::to_string(p - c.begin(k)) + " is not finite");
            if (idx.empty() || c.points[idx.back()] != q) idx.push_back(p);
        }
        const bool closed = c.isClosed(k) && idx.size() >= 3;
        if (closed && c.points[idx.back()] == c.points[idx.front()]) idx.pop_back();
        const size_t n = idx.size();
        if (n < 2 || (closed && n < 3)) {
            g.curveSegments.push_back(static_cast<uint32_t>(g.segments.size()));
            continue;
        }
        // Step 2: arc length in ply radii.
        std::vector<double> arc(n + 1, 0.0);
        for (size_t i = 1; i <= n; ++i) {
            if (i == n && !closed) break;
            arc[i] = arc[i - 1] + glm::length(c.points[idx[i % n]] - c.points[idx[i - 1]]) * invR;
        }
        double total = closed ? arc[n] : arc[n - 1];
        // Closed: whole fiber turns around the loop (no texture seam where it closes).
        const double twist = std::abs(fiberTwist);
        if (closed && twist > 0 && total > 0) {
            const double turns = std::max(1.0, std::round(twist * total / (2.0 * kPi)));
            const double scale = turns * 2.0 * kPi / (twist * total);
            for (double& a : arc) a *= scale;
            total *= scale;
        }
        auto push = [&](size_t i, double a) {
            const glm::vec3 q = g.toScene(c.points[idx[i]]);
            g.points.emplace_back(q.x, q.y, q.z, g.radius);
            g.radial.emplace_back(glm::vec3(plies.radial[idx[i]]));
            if (!plies.colour.empty()) g.colour.push_back(plies.colour[idx[i]]);
            g.arc.push_back(static_cast<float>(a));
        };
        // Step 3: expanded points and segments with neighbour flags.
        const uint32_t base = static_cast<uint32_t>(g.points.size());
        if (closed) {
            push(n - 1, arc[n - 1] - total);
            for (size_t i = 0; i < n; ++i) push(i, arc[i]);
            push(0, total);
            push(1, total + arc[1]);
            for (size_t i = 0; i < n; ++i) {
                g.segments.push_back(base + 1 + static_cast<uint32_t>(i));
                g.flags.push_back(3);
                g.curveOfSegment.push_back(static_cast<uint32_t>(k));
            }
        } else {
            for (size_t i = 0; i < n; ++i) push(i, arc[i]);
            for (size_t i = 0; i + 1 < n; ++i) {
                g.segments.push_back(base + static_cast<uint32_t>(i));
                g.flags.push_back(static_cast<uint8_t>((i > 0 ? 1 : 0) | (i + 2 < n ? 2 : 0)));
                g.curveOfSegment.push_back(static_cast<uint32_t>(k));
            }
        }
        g.curveSegments.push_back(static_cast<uint32_t>(g.segments.size()));
    }
    if (g.segments.empty()) throw Error("cannot render: the ply curves have no segment of non-zero length");
    return g;
}

std::vector<int64_t> segmentCells(const Scene& scene, const PlyGeometry& g) {
    const Binding& b = scene.binding();
    const MappedYarns& yarns = scene.yarns();
    const BaseMesh& mesh = scene.mesh();
    const glm::dvec2 cell = scene.grid().cellSize;
    if (!(cell.x > 0) || !(cell.y > 0))
        throw Error("cannot render: grid mode needs the scene's UV grid (cell size is zero)");
    if (b.vertexCount() == 0 || b.vertexCount() != yarns.curves.pointCount() || b.offsets != yarns.curves.offsets)
        throw Error(
            "cannot render: grid mode needs the binding of the scene's yarns (binding and mapped yarns differ)");
    if (scene.plies().yarnOfCurve.size() != scene.plies().curves.curveCount())
        throw Error("cannot render: grid mode needs the yarn of every ply curve");
    // Step 1: UV cell of every yarn vertex from its binding.
    std::vector<int64_t> vertexCell(b.vertexCount());
    for (size_t v = 0; v < b.vertexCount(); ++v) {
        const uint32_t f = b.face[v];
        if (f >= mesh.faceUvs.size())
            throw Error("cannot render: binding vertex " + std::to_string(v) + " names face " + std::to_string(f) +
                        " outside the mesh");
        const glm::uvec3 t = mesh.faceUvs[f];
        const glm::dvec2 w = b.bary[v];
        const glm::dvec2 uv = (1.0 - w.x - w.y) * mesh.uvs[t.x] + w.x * mesh.uvs[t.y] + w.y * mesh.uvs[t.z];
        const int64_t i = static_cast<int64_t>(std::floor(uv.x / cell.x));
        const int64_t j = static_cast<int64_t>(std::floor(uv.y / cell.y));
        vertexCell[v] = (i << 32) | static_cast<uint32_t>(j);
    }
    // Step 2: each ply segment takes the cell of the nearest vertex of its yarn (a window search
    // that follows the ply along the yarn; a full scan when the window loses it).
    std::vector<int64_t> out(g.segmentCount());
    const double far2 = std::pow(4.0 * std::max(scene.yarnRadius(), g.unit * g.radius) + 1e-12, 2);
    // The curves are the scene's plies, then (a view's) yarn-level pieces (impl::renderCurves).
    const size_t plyCurves = scene.plies().curves.curveCount();
    const std::vector<uint32_t>* pieceYarn = scene.detail() ? &scene.detail()->pieces.yarnPieceYarn : nullptr;
    for (size_t k = 0; k + 1 < g.curveSegments.size(); ++k) {
        if (k >= plyCurves && (pieceYarn == nullptr || k - plyCurves >= pieceYarn->size()))
            throw Error("cannot render: grid mode needs the yarn of every curve (curve " + std::to_string(k) +
                        " has none)");
        const uint32_t y = k < plyCurves ? scene.plies().yarnOfCurve[k] : (*pieceYarn)[k - plyCurves];
        if (y >= yarns.curves.curveCount())
            throw Error("cannot render: ply curve " + std::to_string(k) + " names yarn " + std::to_string(y) +
                        " that does not exist");
        const int64_t y0 = yarns.curves.begin(y), n = yarns.curves.size(y);
        if (n == 0) throw Error("cannot render: yarn " + std::to_string(y) + " has no vertices");
        int64_t last = -1;
        for (uint32_t s = g.curveSegments[k]; s < g.curveSegments[k + 1]; ++s) {
            const glm::vec4 a = g.points[g.segments[s]], c = g.points[g.segments[s] + 1];
            const glm::dvec3 mid = g.toWorld(0.5f * (glm::vec3(a) + glm::vec3(c)));
            auto best = [&](int64_t from, int64_t to) {
                double bd = std::numeric_limits<double>::max();
                int64_t bi = 0;
                for (int64_t i = from; i <= to; ++i) {
                    const int64_t w = ((i % n) + n) % n;
                    const glm::dvec3 d = yarns.curves.points[y0 + w] - mid;
                    const double dd = glm::dot(d, d);
                    if (dd < bd) bd = dd, bi = w;
                }
                return std::make_pair(bi, bd);
            };
            auto [bi, bd] = last < 0 ? best(0, n - 1) : best(last - 16, last + 16);
            if (bd > far2 && last >= 0) std::tie(bi, bd) = best(0, n - 1);
            last = bi;
            out[s] = vertexCell[y0 + bi];
        }
    }
    return out;
}

}  // namespace knit
