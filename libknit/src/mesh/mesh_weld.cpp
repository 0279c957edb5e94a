// mesh_weld.cpp — polygons with per-corner UVs to a welded BaseMesh (see mesh_weld.hpp).
#include "mesh_weld.hpp"
#include "knit/error.hpp"
#include "polygon_triangulation.hpp"

#include <array>
#include <unordered_map>

namespace knit::impl {
namespace {

// Exact-key hash for welding (keys hold +0 instead of -0, and no NaN: checked by the caller).
struct Key3Hash {
    size_t operator()(const std::array<double, 3>& k) const {
        size_t h = 1469598103934665603ull;
        for (double d : k) h = (h ^ std::hash<double>()(d)) * 1099511628211ull;
        return h;
    }
};
using Key3Map = std::unordered_map<std::array<double, 3>, uint32_t, Key3Hash>;

}  // namespace

BaseMesh weldPolygons(const std::string& name, const std::vector<glm::dvec3>& points,
                      const std::vector<uint32_t>& faceStart, const std::vector<int>& faceVerts,
                      const std::function<glm::dvec2(uint32_t corner)>& uvOfCorner, const MeshLoadOptions& options,
                      const std::function<std::string(size_t face)>& faceName) {
    const size_t nv = points.size(), nf = faceStart.size() - 1;
    // Step 1: weld (or just compact) the referenced positions, in input order.
    std::vector<char> used(nv, 0);
    for (int v : faceVerts) used[size_t(v)] = 1;
    BaseMesh mesh;
    mesh.name = name;
    std::vector<uint32_t> remap(nv, 0);
    Key3Map welded;
    for (size_t i = 0; i < nv; ++i) {
        if (!used[i]) continue;
        const glm::dvec3 p = points[i] + glm::dvec3(0.0);  // -0 + 0 = +0: -0 and +0 weld
        if (options.weldEqualPositions) {
            auto [it, inserted] = welded.emplace(std::array<double, 3>{p.x, p.y, p.z}, uint32_t(mesh.positions.size()));
            if (inserted) mesh.positions.push_back(p);
            remap[i] = it->second;
        } else {
            remap[i] = uint32_t(mesh.positions.size());
            mesh.positions.push_back(p);
        }
    }
    // Step 2: UV vertices, one per distinct (welded position, uv), in first-use order; triangulate.
    Key3Map uvIndex;
    auto uvOf = [&](uint32_t pos, glm::dvec2 uv) {
        uv += glm::dvec2(0.0);
        auto [it, inserted] =
            uvIndex.emplace(std::array<double, 3>{double(pos), uv.x, uv.y}, uint32_t(mesh.uvs.size()));
        if (inserted) mesh.uvs.push_back(uv);
        return it->second;
    };
    std::vector<uint32_t> P, U;
    std::vector<glm::dvec3> corners;
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t b = faceStart[f], e = faceStart[f + 1];
        P.resize(e - b);
        U.resize(e - b);
        for (uint32_t c = b; c < e; ++c) {
            const uint32_t v = remap[size_t(faceVerts[c])];
            P[c - b] = v;
            U[c - b] = uvOf(v, uvOfCorner(c));
        }
        corners.resize(P.size());
        for (size_t k = 0; k < P.size(); ++k) corners[k] = mesh.positions[P[k]];
        const PolygonTriangles split = triangulatePolygon(corners);
        if (!split.problem.empty())
            throw Error(name + ": " + (faceName ? faceName(f) : "face " + std::to_string(f)) + " " + split.problem +
                        "; split it into triangles or simple polygons");
        for (const std::array<uint32_t, 3>& t : split.triangles) {
            mesh.faces.emplace_back(P[t[0]], P[t[1]], P[t[2]]);
            mesh.faceUvs.emplace_back(U[t[0]], U[t[1]], U[t[2]]);
        }
    }
    return mesh;
}

}  // namespace knit::impl
