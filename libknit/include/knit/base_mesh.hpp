// knit/base_mesh.hpp — the triangle mesh the knit is draped on: 3D topology + UV charts.
//
// Positions and UVs are indexed separately (like OBJ `v`/`vt`): a position with several UVs is
// a seam. Loaders weld positions that are exactly equal, so formats that duplicate vertices at
// seams (PLY/OFF with per-vertex UVs) get the same 3D topology as OBJ, and vertex normals are
// continuous across seams.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/budget.hpp"

namespace knit {

struct BaseMesh {
    std::string name;                   // file or built-in name, for messages
    std::vector<glm::dvec3> positions;  // 3D vertices (metres)
    std::vector<glm::dvec2> uvs;        // UV vertices
    std::vector<glm::uvec3> faces;      // triangle -> position indices
    std::vector<glm::uvec3> faceUvs;    // triangle -> uv indices (same size as faces)

    size_t faceCount() const { return faces.size(); }
};

// A point on the surface: a triangle and barycentric coordinates (b0, b1, b2), sum 1.
struct SurfacePoint {
    uint32_t face = 0;
    glm::dvec3 bary{1.0, 0.0, 0.0};

    template <class T>
    T interpolate(const std::vector<T>& perVertex, const std::vector<glm::uvec3>& faces) const {
        const glm::uvec3 f = faces[face];
        return perVertex[f.x] * bary.x + perVertex[f.y] * bary.y + perVertex[f.z] * bary.z;
    }
};

struct MeshLoadOptions {
    // Weld positions that are bit-identical into one topology vertex (see file comment).
    bool weldEqualPositions = true;
    // glTF: refuse files whose primitives, instanced by the node tree, expand to more vertices
    // or triangles than this (instancing can multiply a small file).
    uint64_t maxElements = uint64_t(1) << 28;
    // glTF: the memory the expanded vertices and triangles of all instances need, estimated
    // before any is expanded, must fit this budget (the CLI passes --max-memory).
    MemoryBudget budget;
};

// Reads OBJ (with vt), PLY (with per-vertex u,v / s,t / texture_u,texture_v) or OFF (with
// texture coords), each in one pass by libknit's own reader (src/mesh/mesh_*.cpp), or glTF 2.0 (.gltf / .glb, TEXCOORD_0; src/mesh/mesh_gltf.cpp),
// chosen by extension (src/mesh/mesh_io.cpp); polygons are fan-triangulated. Throws knit::Error
// naming the file when it cannot be read, is empty, has no UVs, or has NaN/Inf coordinates.
BaseMesh loadMesh(const std::string& path, const MeshLoadOptions& options = {});

// glTF 2.0 base meshes (src/mesh_gltf.cpp has the details): the triangle primitives of the
// default scene with their node transforms; uv = (u, 1 - v) of TEXCOORD_0, because glTF's
// texture origin is the top-left corner and libknit's (like OBJ's) the bottom-left.
BaseMesh loadGltfMesh(const std::string& path, const MeshLoadOptions& options = {});
// The same from memory (GLB when `bytes` starts with "glTF", else JSON); external buffers are
// read relative to `baseDir` (empty: external files are refused). `name` is used in messages.
BaseMesh parseGltfMesh(const std::string& bytes, const std::string& name, const std::string& baseDir,
                       const MeshLoadOptions& options = {});

// Built-in procedural meshes; all have UVs in [0,1]^2 and are +Y up (glTF's convention).
struct ProceduralMeshOptions {
    int resU = 32, resV = 32;  // quads along u and v
    double size = 0.5;         // plane / drape: side length (m)
    double radius = 0.1;       // cylinder / sphere radius (m)
    double height = 0.3;       // cylinder height (m)
};
BaseMesh makePlane(const ProceduralMeshOptions& o = {});     // y = 0, centred: uv = (x/size + 0.5, 0.5 - z/size)
BaseMesh makeCylinder(const ProceduralMeshOptions& o = {});  // u around (seam at u = 0/1), v along +y
BaseMesh makeSphere(const ProceduralMeshOptions& o = {});    // latitude-longitude, seam at u = 0/1
BaseMesh makeDrape(const ProceduralMeshOptions& o = {});     // square sheet draped over a sphere (top at +y)
std::vector<std::string> builtinMeshNames();
BaseMesh builtinMesh(const std::string& name, const ProceduralMeshOptions& o = {});
// A mesh from a file or a built-in name.
BaseMesh loadMeshFileOrName(const std::string& fileOrName, const ProceduralMeshOptions& o = {},
                            const MeshLoadOptions& load = {});

// Angle-weighted vertex normals on the 3D topology (continuous across UV seams). Vertices
// without a non-degenerate face get (0, 0, 1).
std::vector<glm::dvec3> vertexNormals(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& faces);

// Metres per UV unit: area-weighted ratio of 3D to UV edge lengths, per axis direction
// (x: along u, y: along v), from triangles with non-degenerate UVs.
glm::dvec2 uvToMetreScale(const BaseMesh& mesh);

// The triangles `faces` (indices into mesh.faces) as a mesh of their own: only the positions and
// UVs they use, renumbered in order of first use; the name gets `suffix`. Throws knit::Error for
// a face index out of range.
BaseMesh meshSubset(const BaseMesh& mesh, const std::vector<uint32_t>& faces, const std::string& suffix = "");

// Checks index ranges, finiteness, that faces exist; throws knit::Error naming the element.
void validateMesh(const BaseMesh& mesh);

}  // namespace knit
