// knit/sweep.hpp — swept tube meshes around curves (plies or yarns), for export and rendering.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "knit/polylines.hpp"

namespace knit {

struct TubeOptions {
    int sides = 8;     // vertices per ring (>= 3)
    bool caps = true;  // close open curve ends
    // Optional frame seed per curve point (indexed like curves.points): the surface normal for
    // yarns, the radial direction for plies. nullptr: frames.hpp's default seed.
    const std::vector<glm::dvec3>* seedNormals = nullptr;
    // Optional linear colour per curve point (indexed like curves.points): each ring (and cap)
    // takes its point's colour into TubeMesh::colours. nullptr: no colours.
    const std::vector<glm::vec3>* pointColours = nullptr;
};

// One ring of `sides` vertices per curve point, oriented by rotation-minimizing frames (rings
// perpendicular to the averaged tangent at joints), shared between consecutive segments.
// Positions are relative to `origin` (a chunk's local origin) so float32 export keeps precision.
struct TubeMesh {
    glm::dvec3 origin{0.0};
    std::vector<glm::vec3> positions;  // relative to origin
    std::vector<glm::vec3> normals;    // unit
    std::vector<glm::vec4> tangents;   // glTF TANGENT: xyz along increasing u, w = bitangent sign
    std::vector<glm::vec2> uvs;        // u: around (0..1), v: along, in radius units
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> curveOfVertex;
    std::vector<glm::vec3> colours;  // linear, per vertex; empty without TubeOptions::pointColours

    size_t vertexCount() const { return positions.size(); }
};

// Sweeps curves [firstCurve, lastCurve) of `curves` with constant `radius`. Chunked callers
// (streaming export) pass sub-ranges.
TubeMesh sweepTubes(const Polylines& curves, double radius, const TubeOptions& options, size_t firstCurve,
                    size_t lastCurve, glm::dvec3 origin);

// Same, writing into `out` and reusing its storage (streaming export sweeps chunk after chunk
// into one mesh, so the memory is allocated and touched once, not once per chunk).
void sweepTubes(const Polylines& curves, double radius, const TubeOptions& options, size_t firstCurve, size_t lastCurve,
                glm::dvec3 origin, TubeMesh& out);

// Layout (see sweep.cpp): every ring stores sides + 1 vertices (the last one duplicates the
// first position with u = 1, the texture seam); a closed curve of n points gets n + 1 rings (the
// last duplicates ring 0 with v = length / radius); an open curve with caps adds one cap per end
// (a centre vertex + `sides` rim vertices with normal -+tangent). Curves with < 2 points give
// nothing. These give the counts sweepTubes produces for one curve (for chunk planning).
size_t tubeVertexCount(uint32_t points, bool closed, const TubeOptions& options);
size_t tubeTriangleCount(uint32_t points, bool closed, const TubeOptions& options);

// Size estimates before sweeping (memory budgets): the vertices and triangles sweepTubes makes
// for all `curves`, the largest curve's vertices, and the bytes of a TubeMesh of given counts.
struct TubeCounts {
    double vertices = 0, triangles = 0;
    size_t largestCurveVertices = 0;
};
TubeCounts tubeCounts(const Polylines& curves, const TubeOptions& options);
double tubeMeshBytes(double vertices, double triangles);

}  // namespace knit
