// mesh_reader.hpp (internal) — what the file readers behind loadMesh share: the reader
// signature of the dispatch table (mesh_io.cpp), the polygons a reader hands on, the checks of
// number tokens, and buildPolygonMesh, the common end of every OBJ/PLY/OFF reader (face checks,
// welding, triangulation).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"

namespace knit::impl {

// One reader per format, called by loadMesh once the file is known to be a regular file.
BaseMesh readObjMesh(const std::string& path, const MeshLoadOptions& options);  // mesh_obj.cpp
BaseMesh readPlyMesh(const std::string& path, const MeshLoadOptions& options);  // mesh_ply.cpp
BaseMesh readOffMesh(const std::string& path, const MeshLoadOptions& options);  // mesh_off.cpp

[[noreturn]] void failMesh(const std::string& file, const std::string& what);                   // "file: what"
[[noreturn]] void failMeshLine(const std::string& file, size_t line, const std::string& what);  // "file:line: what"

// A token that is a whole, finite number ("1.5e-3"; not "nan", "inf", "1e400", "1.0abc").
bool parseFinite(const std::string& token, double& value);
// "0x1p3": a number to strtod, not to a mesh reader (OpenMesh's, which libknit used before for
// OBJ and OFF, read the 0 and went on from the 'x'); refused.
bool isHexNumber(const std::string& token);
// A whole, non-zero integer token (OBJ indices, PLY counts).
bool parseIndex(const std::string& token, long& value);
// A parsed number the mesh stores as float32 (UVs; PLY/OFF positions): beyond +-3.4e38 it would
// be garbage, so the line and the value are named.
void requireFloatRange(const std::string& path, size_t lineNo, const std::string& token, double value);
std::string trimmed(std::string s);

// Polygons as read: polygon k = faceVerts[faceStart[k] .. faceStart[k+1]); per-corner texture
// coordinates (OBJ) in the same layout as faceVerts, float32 as the readers store them.
struct Polygons {
    std::vector<uint32_t> faceStart{0};
    std::vector<int> faceVerts;
    std::vector<glm::vec2> cornerUv;
    std::vector<char> faceHasCornerUv;
    std::vector<char> faceCornerUvMismatch;  // texcoord count != corner count
    size_t count() const { return faceStart.size() - 1; }
};

// Triangulated, welded BaseMesh from what a reader recorded: checks every polygon (>= 3 corners,
// indices in range, no repeated vertex, finite UVs present) naming it (with its line when
// `faceLines` is given), then impl::weldPolygons. UVs per corner (`cornerUvs`) or per vertex.
BaseMesh buildPolygonMesh(const std::string& path, const Polygons& polys, const std::vector<glm::dvec3>& points,
                          const std::vector<glm::dvec2>& vertexUv, bool cornerUvs, const std::vector<size_t>* faceLines,
                          const MeshLoadOptions& options);

}  // namespace knit::impl
