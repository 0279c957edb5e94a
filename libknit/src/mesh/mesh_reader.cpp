// mesh_reader.cpp — what the OBJ/PLY/OFF readers share (mesh_reader.hpp): failure messages,
// number tokens, and the polygon checks before welding.
#include "mesh_reader.hpp"

#include "knit/error.hpp"
#include "mesh_weld.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace knit::impl {

void failMesh(const std::string& file, const std::string& what) { throw Error(file + ": " + what); }
void failMeshLine(const std::string& file, size_t line, const std::string& what) {
    throw Error(file + ":" + std::to_string(line) + ": " + what);
}

bool parseFinite(const std::string& token, double& value) {
    if (token.empty()) return false;
    errno = 0;
    char* end = nullptr;
    value = std::strtod(token.c_str(), &end);
    return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(value);
}

void requireFloatRange(const std::string& path, size_t lineNo, const std::string& token, double value) {
    if (std::abs(value) > double(std::numeric_limits<float>::max()))
        failMeshLine(path, lineNo, "'" + token + "' is beyond the float32 range (3.4e38) of mesh coordinates");
}

bool isHexNumber(const std::string& token) {
    const size_t s = !token.empty() && (token[0] == '-' || token[0] == '+') ? 1 : 0;
    return token.size() > s + 1 && token[s] == '0' && (token[s + 1] == 'x' || token[s + 1] == 'X');
}

bool parseIndex(const std::string& token, long& value) {
    if (token.empty()) return false;
    errno = 0;
    char* end = nullptr;
    value = std::strtol(token.c_str(), &end, 10);
    return end == token.c_str() + token.size() && errno != ERANGE && value != 0;
}

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    size_t b = 0;
    while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    return s.substr(b);
}

BaseMesh buildPolygonMesh(const std::string& path, const Polygons& polys, const std::vector<glm::dvec3>& points,
                          const std::vector<glm::dvec2>& vertexUv, bool cornerUvs, const std::vector<size_t>* faceLines,
                          const MeshLoadOptions& options) {
    const size_t nv = points.size(), nf = polys.count();
    auto faceName = [&](size_t f) {
        return faceLines ? "face " + std::to_string(f) + " (line " + std::to_string((*faceLines)[f]) + ")"
                         : "face " + std::to_string(f);
    };
    auto cornerUv = [&](uint32_t c) { return glm::dvec2(polys.cornerUv[c].x, polys.cornerUv[c].y); };
    if (nf == 0) failMesh(path, "the mesh has no faces");
    // Check positions and UVs are finite.
    for (size_t i = 0; i < nv; ++i)
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
            failMesh(path, "vertex " + std::to_string(i) + " has a non-finite position");
    // Check the polygons: >= 3 corners, indices in range, no repeated vertex, UVs present.
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t b = polys.faceStart[f], e = polys.faceStart[f + 1];
        if (e - b < 3)
            failMesh(path, faceName(f) + " has " + std::to_string(e - b) +
                               " corners (malformed file, or a non-numeric value such as nan in ASCII data?)");
        for (uint32_t c = b; c < e; ++c) {
            const int v = polys.faceVerts[c];
            if (v < 0 || size_t(v) >= nv)
                failMesh(path, faceName(f) + " references vertex " + std::to_string(v) + " but the file has " +
                                   std::to_string(nv) + " vertices");
            for (uint32_t d = b; d < c; ++d)
                if (polys.faceVerts[d] == v)
                    failMesh(path, faceName(f) + " uses vertex " + std::to_string(v) +
                                       " twice (malformed or truncated file?)");
            const glm::dvec2 uv = cornerUvs ? cornerUv(c) : vertexUv[v];
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                failMesh(path, faceName(f) + " has a non-finite texture coordinate at vertex " + std::to_string(v));
        }
        if (cornerUvs && (polys.faceCornerUvMismatch[f] || !polys.faceHasCornerUv[f]))
            failMesh(path, faceName(f) + ": texture coordinates missing or not one per corner");
    }
    // Weld and triangulate (a polygon that cannot be is named with its line).
    return weldPolygons(
        path, points, polys.faceStart, polys.faceVerts,
        [&](uint32_t c) { return cornerUvs ? cornerUv(c) : vertexUv[size_t(polys.faceVerts[c])]; }, options, faceName);
}

}  // namespace knit::impl
