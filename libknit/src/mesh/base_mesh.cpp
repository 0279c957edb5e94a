// base_mesh.cpp — measures and checks on a BaseMesh: vertex normals, UV-to-metre scale,
// validation, and the file-or-built-in-name front door.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/platform.hpp"
#include "util/csr.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace knit {
namespace {

std::string prefix(const BaseMesh& m) { return m.name.empty() ? std::string("mesh: ") : m.name + ": "; }

std::string str(const glm::dvec3& p) {
    return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}
std::string str(const glm::dvec2& p) { return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")"; }

// A triangle whose edge cross product is this small relative to its edge lengths has no
// meaningful normal direction (sin of its largest angle below ~1e-12 or a zero-length edge).
constexpr double kDegenerateSin = 1e-12;

// +1 / -1 per face so that faces sharing a manifold edge traverse it in opposite directions
// (consistent winding); empty when the winding is consistent already (the common case: one pass
// over the vertex fans, no further work: ~1.2x the time of the normals alone). Otherwise each edge-connected component is re-wound
// by a breadth-first walk from its lowest face and then keeps the winding of the larger 3D area,
// so a few wrongly wound faces are corrected rather than the rest of the surface. Edges of
// more than two faces (non-manifold) and faces repeating a vertex impose no constraint; a
// non-orientable component keeps the walk's choice.
std::vector<int8_t> windingSigns(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& faces) {
    const size_t nf = faces.size(), nv = positions.size();
    auto proper = [&](const glm::uvec3& t) { return t.x != t.y && t.y != t.z && t.z != t.x; };
    // Vertex -> faces (CSR), proper faces only.
    std::vector<uint32_t> start(nv + 1, 0), fan;
    for (const glm::uvec3& t : faces)
        if (proper(t))
            for (int k = 0; k < 3; ++k) ++start[t[k] + 1];
    util::countsToOffsets(start);
    fan.resize(start[nv]);
    {
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (size_t f = 0; f < nf; ++f)
            if (proper(faces[f]))
                for (int k = 0; k < 3; ++k) fan[fill[faces[f][k]]++] = uint32_t(f);
    }
    // Detection, per vertex a: two faces of a's fan leaving a towards the same vertex b use the
    // edge a -> b in the same direction; when they are the only two faces on that edge, the
    // winding is inconsistent (more faces: a non-manifold edge, no constraint).
    auto next = [&](uint32_t f, uint32_t a) {
        const glm::uvec3 t = faces[f];
        return t.x == a ? t.y : (t.y == a ? t.z : t.x);
    };
    std::vector<uint8_t> vertexInconsistent(nv, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t a = r.begin(); a != r.end(); ++a) {
            for (uint32_t i = start[a]; i < start[a + 1] && !vertexInconsistent[a]; ++i) {
                const uint32_t b = next(fan[i], uint32_t(a));
                for (uint32_t j = i + 1; j < start[a + 1]; ++j) {
                    if (next(fan[j], uint32_t(a)) != b) continue;
                    uint32_t onEdge = 0;
                    for (uint32_t k = start[a]; k < start[a + 1]; ++k) {
                        const glm::uvec3 t = faces[fan[k]];
                        onEdge += t.x == b || t.y == b || t.z == b;
                    }
                    if (onEdge == 2) vertexInconsistent[a] = 1;
                    break;
                }
            }
        }
    });
    if (std::find(vertexInconsistent.begin(), vertexInconsistent.end(), 1) == vertexInconsistent.end()) return {};
    // The one other face across each corner's edge (k -> k+1), and whether it uses the edge in
    // the same direction (inconsistent winding). UINT32_MAX: boundary or non-manifold edge.
    std::vector<uint32_t> across(3 * nf, UINT32_MAX);
    std::vector<uint8_t> sameDirection(3 * nf, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nf, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t f = r.begin(); f != r.end(); ++f) {
            const glm::uvec3 t = faces[f];
            if (!proper(t)) continue;
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = t[k], b = t[(k + 1) % 3];
                uint32_t other = UINT32_MAX, count = 0;
                bool same = false;
                for (uint32_t i = start[a]; i < start[a + 1]; ++i) {
                    const uint32_t g = fan[i];
                    if (g == f) continue;
                    const glm::uvec3 u = faces[g];
                    for (int m = 0; m < 3; ++m) {
                        if (u[m] != a) continue;
                        if (u[(m + 1) % 3] == b) ++count, other = g, same = true;
                        else if (u[(m + 2) % 3] == b) ++count, other = g, same = false;
                    }
                }
                if (count != 1) continue;
                across[3 * f + k] = other;
                sameDirection[3 * f + k] = same;
            }
        }
    });
    // Breadth-first re-winding per component; the larger-area winding wins.
    std::vector<int8_t> sign(nf, 0);
    std::vector<uint32_t> queue;
    for (size_t seed = 0; seed < nf; ++seed) {
        if (sign[seed] != 0) continue;
        sign[seed] = 1;
        queue.assign(1, uint32_t(seed));
        double area[2] = {0, 0};  // [0]: faces keeping their winding, [1]: flipped ones
        for (size_t q = 0; q < queue.size(); ++q) {
            const uint32_t f = queue[q];
            const glm::uvec3 t = faces[f];
            area[sign[f] < 0] +=
                glm::length(glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]));
            for (int k = 0; k < 3; ++k) {
                const uint32_t g = across[3 * f + k];
                if (g == UINT32_MAX || sign[g] != 0) continue;
                sign[g] = int8_t(sameDirection[3 * f + k] ? -sign[f] : sign[f]);
                queue.push_back(g);
            }
        }
        if (area[1] > area[0])
            for (uint32_t f : queue) sign[f] = int8_t(-sign[f]);
    }
    return sign;
}

}  // namespace

// Angle-weighted vertex normals (Thürmer & Wüthrich): every non-degenerate triangle adds its unit
// normal times its interior angle at the corner to the corner's 3D vertex. Seam copies of a
// vertex are one position index, so the normal is the same on both sides of a UV seam.
// Faces wound against their neighbours count with their normal reversed (windingSigns), so an
// inconsistently oriented mesh gets the normals of its consistently wound version instead of
// cancelling ones (tests/hard: inconsistentOrientation).
// Per-corner contributions are computed in parallel and summed in face order (deterministic).
std::vector<glm::dvec3> vertexNormals(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& faces) {
    // Step 0: winding signs (empty: consistent winding).
    const std::vector<int8_t> sign = windingSigns(positions, faces);
    // Step 1: weighted normal per face corner.
    std::vector<glm::dvec3> corner(faces.size() * 3, glm::dvec3(0.0));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, faces.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t f = r.begin(); f != r.end(); ++f) {
            const glm::uvec3 t = faces[f];
            assert(t.x < positions.size() && t.y < positions.size() && t.z < positions.size());
            const glm::dvec3 p[3] = {positions[t.x], positions[t.y], positions[t.z]};
            const glm::dvec3 e[3] = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};  // e[k]: corner k -> k+1
            const glm::dvec3 c = glm::cross(e[0], -e[2]);
            const double len = glm::length(c);
            const double maxEdge2 = std::max({glm::dot(e[0], e[0]), glm::dot(e[1], e[1]), glm::dot(e[2], e[2])});
            if (!(len > kDegenerateSin * maxEdge2)) continue;
            const glm::dvec3 n = (sign.empty() || sign[f] > 0 ? 1.0 : -1.0) * c / len;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 a = e[k], b = -e[(k + 2) % 3];  // the two edges leaving corner k
                const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
                corner[3 * f + k] = angle * n;
            }
        }
    });
    // Step 2: sum per vertex in face order, then normalize; no contribution -> (0, 0, 1).
    std::vector<glm::dvec3> normals(positions.size(), glm::dvec3(0.0));
    for (size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) normals[faces[f][k]] += corner[3 * f + k];
    for (glm::dvec3& n : normals) {
        const double len = glm::length(n);
        n = util::positiveFinite(len) ? n / len : glm::dvec3(0.0, 0.0, 1.0);
    }
    return normals;
}

// Metres per UV unit along u (x) and along v (y). Per triangle, the affine map UV -> 3D has the
// Jacobian J = [dX/du, dX/dv] = [p1-p0, p2-p0] · [uv1-uv0, uv2-uv0]^-1; its column lengths
// |dX/du| and |dX/dv| are the metres per unit u and per unit v in that triangle. The result is
// their average weighted by UV triangle area (the mean 3D length of iso-v / iso-u lines per UV
// unit), over triangles whose UV triangle is not degenerate (|det| > 1e-12 · |uv1-uv0| ·
// |uv2-uv0|) and whose 3D area is > 0. Weighting by UV area keeps the average bounded by the
// mesh's 3D size: a near-degenerate UV sliver (stretch ~1e12) contributes its 3D width, not
// its stretch times its 3D area (tests/hard: uvNearZeroAreaTriangles). A size-s plane gives
// (s, s); a cylinder gives (2πR, height). Throws knit::Error for an invalid mesh (validateMesh)
// or when no triangle qualifies.
BaseMesh meshSubset(const BaseMesh& mesh, const std::vector<uint32_t>& faces, const std::string& suffix) {
    BaseMesh out;
    out.name = mesh.name + suffix;
    const bool uvs = mesh.faceUvs.size() == mesh.faces.size();
    std::vector<uint32_t> position(mesh.positions.size(), UINT32_MAX), uv(mesh.uvs.size(), UINT32_MAX);
    // Renumbers index i of `from` into `to` on first use.
    const auto take = [](std::vector<uint32_t>& map, uint32_t i, const auto& from, auto& to) {
        if (map[i] == UINT32_MAX) {
            map[i] = static_cast<uint32_t>(to.size());
            to.push_back(from[i]);
        }
        return map[i];
    };
    for (const uint32_t f : faces) {
        if (f >= mesh.faces.size())
            throw Error("mesh '" + mesh.name + "' has no triangle " + std::to_string(f) + " (it has " +
                        std::to_string(mesh.faces.size()) + ")");
        glm::uvec3 p, t;
        for (int k = 0; k < 3; ++k) {
            p[k] = take(position, mesh.faces[f][k], mesh.positions, out.positions);
            if (uvs) t[k] = take(uv, mesh.faceUvs[f][k], mesh.uvs, out.uvs);
        }
        out.faces.push_back(p);
        if (uvs) out.faceUvs.push_back(t);
    }
    return out;
}

glm::dvec2 uvToMetreScale(const BaseMesh& mesh) {
    validateMesh(mesh);
    double sumA = 0.0, sumU = 0.0, sumV = 0.0;
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
        const glm::uvec3 t = mesh.faces[f], tu = mesh.faceUvs[f];
        const glm::dvec3 dp1 = mesh.positions[t.y] - mesh.positions[t.x];
        const glm::dvec3 dp2 = mesh.positions[t.z] - mesh.positions[t.x];
        const glm::dvec2 du1 = mesh.uvs[tu.y] - mesh.uvs[tu.x];
        const glm::dvec2 du2 = mesh.uvs[tu.z] - mesh.uvs[tu.x];
        const double det = du1.x * du2.y - du2.x * du1.y;
        if (!(std::abs(det) > 1e-12 * glm::length(du1) * glm::length(du2))) continue;
        const double area = 0.5 * glm::length(glm::cross(dp1, dp2));
        if (!util::positiveFinite(area)) continue;
        const double uvArea = 0.5 * std::abs(det);
        // [dX/du dX/dv] = [dp1 dp2] · inverse([du1 du2]).
        const glm::dvec3 dXdu = (dp1 * du2.y - dp2 * du1.y) / det;
        const glm::dvec3 dXdv = (dp2 * du1.x - dp1 * du2.x) / det;
        sumA += uvArea;
        sumU += uvArea * glm::length(dXdu);
        sumV += uvArea * glm::length(dXdv);
    }
    if (!(sumA > 0.0))
        throw Error(prefix(mesh) + "no triangle has both a non-degenerate UV triangle and a positive 3D area, "
                                   "so the UV-to-metre scale is undefined");
    return {sumU / sumA, sumV / sumA};
}

// Boundary check of a mesh: non-empty, matching face arrays, indices in range, finite values.
void validateMesh(const BaseMesh& mesh) {
    const std::string p = prefix(mesh);
    if (mesh.faces.empty()) throw Error(p + "the mesh has no faces");
    if (mesh.faces.size() != mesh.faceUvs.size())
        throw Error(p + "the mesh has " + std::to_string(mesh.faces.size()) + " faces but " +
                    std::to_string(mesh.faceUvs.size()) + " UV faces (must be equal)");
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        if (!util::finite(mesh.positions[i]))
            throw Error(p + "position " + std::to_string(i) + " is not finite " + str(mesh.positions[i]));
    for (size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!util::finite(mesh.uvs[i]))
            throw Error(p + "uv " + std::to_string(i) + " is not finite " + str(mesh.uvs[i]));
    for (size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            if (mesh.faces[f][k] >= mesh.positions.size())
                throw Error(p + "face " + std::to_string(f) + " references position " +
                            std::to_string(mesh.faces[f][k]) + " but the mesh has " +
                            std::to_string(mesh.positions.size()) + " positions");
            if (mesh.faceUvs[f][k] >= mesh.uvs.size())
                throw Error(p + "face " + std::to_string(f) + " references uv " + std::to_string(mesh.faceUvs[f][k]) +
                            " but the mesh has " + std::to_string(mesh.uvs.size()) + " uvs");
        }
}

std::vector<std::string> builtinMeshNames() { return {"plane", "cylinder", "sphere", "drape"}; }

BaseMesh builtinMesh(const std::string& name, const ProceduralMeshOptions& o) {
    if (name == "plane") return makePlane(o);
    if (name == "cylinder") return makeCylinder(o);
    if (name == "sphere") return makeSphere(o);
    if (name == "drape") return makeDrape(o);
    std::string known;
    for (const std::string& n : builtinMeshNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown built-in mesh '" + name + "' (known: " + known + ")");
}

// A string is a file when it names an existing path (a directory is passed on to loadMesh, which
// rejects it) or ends in a mesh extension (.obj/.ply/.off/.gltf/.glb, any case: a missing file is
// then reported as missing); anything else is a built-in name.
BaseMesh loadMeshFileOrName(const std::string& fileOrName, const ProceduralMeshOptions& o,
                            const MeshLoadOptions& load) {
    std::error_code ec;
    const std::string ext = util::lowerExtension(fileOrName);
    const bool meshExt = ext == "obj" || ext == "ply" || ext == "off" || ext == "gltf" || ext == "glb";
    if (meshExt || std::filesystem::exists(fileOrName, ec)) return loadMesh(fileOrName, load);
    const auto names = builtinMeshNames();
    if (std::find(names.begin(), names.end(), fileOrName) == names.end()) {
        std::string known;
        for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
        throw Error("'" + fileOrName +
                    "' is neither a mesh file (.obj, .ply, .off, .gltf, .glb) nor a built-in mesh (" + known + ")");
    }
    // The mesh itself is 88 bytes per quad (the peak resident set of knit.load_mesh("plane", 2000,
    // 2000) minus before), and the pipeline keeps more per triangle (normals, the UV grid's lists,
    // the binding's lookups): `knit build -q --mesh plane --mesh-res 4096 --repeats 1 1 -o o.obj`
    // peaked at 5.14 GB (/usr/bin/time), 307 bytes per quad, where this estimate of the mesh alone
    // (128 bytes) let it pass a 4 GiB budget into std::bad_alloc. 320 bytes per quad covers it.
    const double quads = double(std::max(o.resU, 0)) * double(std::max(o.resV, 0));
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", quads);
    load.budget.require(320.0 * quads, std::string(count) + " quads of the built-in mesh '" + fileOrName + "'",
                        "the mesh resolution");
    return builtinMesh(fileOrName, o);
}

}  // namespace knit
