// base_mesh.cpp — measures and checks on a BaseMesh: vertex normals, UV-to-metre scale,
// validation, and the file-or-built-in-name front door.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <filesystem>

namespace knit {
namespace {

std::string prefix(const BaseMesh& m) { return m.name.empty() ? std::string("mesh: ") : m.name + ": "; }

bool finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
bool finite(const glm::dvec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::string str(const glm::dvec3& p) {
    return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}
std::string str(const glm::dvec2& p) { return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")"; }

// A triangle whose edge cross product is this small relative to its edge lengths has no
// meaningful normal direction (sin of its largest angle below ~1e-12 or a zero-length edge).
constexpr double kDegenerateSin = 1e-12;

}  // namespace

// Angle-weighted vertex normals (Thürmer & Wüthrich): every non-degenerate triangle adds its unit
// normal times its interior angle at the corner to the corner's 3D vertex. Seam copies of a
// vertex are one position index, so the normal is the same on both sides of a UV seam.
// Per-corner contributions are computed in parallel and summed in face order (deterministic).
std::vector<glm::dvec3> vertexNormals(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& faces) {
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
            const glm::dvec3 n = c / len;
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
        n = len > 0.0 && std::isfinite(len) ? n / len : glm::dvec3(0.0, 0.0, 1.0);
    }
    return normals;
}

// Metres per UV unit along u (x) and along v (y). Per triangle, the affine map UV -> 3D has the
// Jacobian J = [dX/du, dX/dv] = [p1-p0, p2-p0] · [uv1-uv0, uv2-uv0]^-1; its column lengths
// |dX/du| and |dX/dv| are the metres per unit u and per unit v in that triangle. The result is
// their average weighted by 3D triangle area, over triangles whose UV triangle is not degenerate
// (|det| > 1e-12 · |uv1-uv0| · |uv2-uv0|) and whose 3D area is > 0. A size-s plane gives (s, s);
// a cylinder gives (2πR, height). Throws knit::Error for an invalid mesh (validateMesh) or when
// no triangle qualifies.
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
        if (!(area > 0.0) || !std::isfinite(area)) continue;
        // [dX/du dX/dv] = [dp1 dp2] · inverse([du1 du2]).
        const glm::dvec3 dXdu = (dp1 * du2.y - dp2 * du1.y) / det;
        const glm::dvec3 dXdv = (dp2 * du1.x - dp1 * du2.x) / det;
        sumA += area;
        sumU += area * glm::length(dXdu);
        sumV += area * glm::length(dXdv);
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
        if (!finite(mesh.positions[i]))
            throw Error(p + "position " + std::to_string(i) + " is not finite " + str(mesh.positions[i]));
    for (size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!finite(mesh.uvs[i])) throw Error(p + "uv " + std::to_string(i) + " is not finite " + str(mesh.uvs[i]));
    for (size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            if (mesh.faces[f][k] >= mesh.positions.size())
                throw Error(p + "face " + std::to_string(f) + " references position " + std::to_string(mesh.faces[f][k]) +
                            " but the mesh has " + std::to_string(mesh.positions.size()) + " positions");
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
// rejects it) or ends in a mesh extension (.obj/.ply/.off, any case: a missing file is then
// reported as missing); anything else is a built-in name.
BaseMesh loadMeshFileOrName(const std::string& fileOrName, const ProceduralMeshOptions& o) {
    std::error_code ec;
    std::string ext = std::filesystem::path(fileOrName).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool meshExt = ext == ".obj" || ext == ".ply" || ext == ".off";
    if (meshExt || std::filesystem::exists(fileOrName, ec)) return loadMesh(fileOrName);
    const auto names = builtinMeshNames();
    if (std::find(names.begin(), names.end(), fileOrName) == names.end()) {
        std::string known;
        for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
        throw Error("'" + fileOrName + "' is neither a mesh file (.obj, .ply, .off) nor a built-in mesh (" + known + ")");
    }
    return builtinMesh(fileOrName, o);
}

}  // namespace knit
