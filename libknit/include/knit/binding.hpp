// knit/binding.hpp — attach yarn vertices to the base mesh once; evaluate on any pose.
//
// Binding: per yarn vertex (triangle, barycentrics, height). Computed on the rest mesh (cutting
// yarns where they leave the UV region and welding ends that meet again across seams), then
// evaluated as P = sum(b_i x_i) + h * normalize(sum(b_i n_i)) on any mesh with the same
// connectivity (animation: simulate only the base mesh).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"
#include "knit/polylines.hpp"
#include "knit/stitch.hpp"
#include "knit/uv_grid.hpp"

namespace knit {

struct BindOptions {
    double yarnRadius = 0.001;  // object-space yarn radius (metres); tolerances scale with it
    // A point outside every triangle but within this UV distance of one (in units of the yarn
    // radius measured in UV) is clamped onto the closest triangle; farther out it is cut.
    double clampTolerance = 0.01;
    // Cut ends whose boundary crossings meet again in object space within this distance
    // (in yarn radii) with agreeing tangents are welded (UV seams, cylinder courses).
    double weldTolerance = 0.25;
    double weldMinCos = 0.5;  // cosine between the continuing tangents required to weld
    bool weld = true;
};

struct Binding {
    std::vector<uint32_t> face;
    std::vector<glm::dvec2> bary;  // (b1, b2); b0 = 1 - b1 - b2
    std::vector<double> height;
    std::vector<double> twist;
    std::vector<glm::vec3> colour;  // linear yarn colour per vertex; empty without colours
    // Per vertex, the tiled pattern vertex it comes from (UvYarns::source: tile slot x pattern
    // vertex count + pattern vertex; a boundary crossing: the vertex it leaves from), which
    // strain-aware deformation (knit/strain.hpp) looks its displacement up by. Empty when the
    // yarns had no sources.
    std::vector<uint32_t> source;
    std::vector<uint32_t> offsets{0};
    std::vector<uint8_t> closed;

    size_t yarnCount() const { return closed.size(); }
    size_t vertexCount() const { return face.size(); }
};

struct BindStats {
    size_t clampedVertices = 0;   // outside every triangle, within tolerance
    size_t cutVertices = 0;       // dropped: outside the UV region (or isolated single points)
    size_t boundaryVertices = 0;  // inserted where a yarn crosses the UV boundary
    size_t weldedEnds = 0;        // ends joined across seams (2 per weld)
    size_t openEnds = 0;          // remaining open ends (2 per open yarn)
    size_t closedLoops = 0;
};

struct BindResult {
    Binding binding;
    BindStats stats;
};

// `normals`: rest-pose vertex normals of `mesh` (vertexNormals), used to place seam welds.
// Throws knit::Error for invalid options.
BindResult bindYarns(const BaseMesh& mesh, const std::vector<glm::dvec3>& normals, const UvGrid& grid,
                     const UvYarns& yarns, const BindOptions& options);

// Yarn centrelines in object space plus the interpolated surface normal at each vertex.
struct MappedYarns {
    Polylines curves;
    std::vector<glm::dvec3> normals;
    std::vector<glm::vec3> colour;  // linear yarn colour per point; empty without colours
    // Per point: the twist change (radians) a strain table gives it, added to the ply phase
    // (knit/strain.hpp); empty without strain-aware deformation or when the table has no twist.
    std::vector<float> twist;
};

// The hot loop: a flat gather over the binding. `positions`/`normals` are per mesh vertex
// (same connectivity as at binding time). Writes into `out` (resized as needed).
void evaluateBinding(const Binding& binding, const std::vector<glm::uvec3>& faces,
                     const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                     MappedYarns& out);

// The same evaluation for a renderer or GPU upload per animation frame: positions only, as
// float32 relative to `origin` (a local origin near the garment keeps sub-micron precision),
// computed in float32 from the mesh converted once per call (positions minus the origin in
// double, then rounded; barycentrics and heights rounded as read): a few float32 roundings of
// the coordinates' size (4e-8 m on a garment of ~0.5 m around the origin; test
// Mapping.floatEvaluationFarFromOriginKeepsPrecision). Bit for bit evaluatePackedFloat on
// packBinding(binding).
void evaluateBindingFloat(const Binding& binding, const std::vector<glm::uvec3>& faces,
                          const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                          glm::dvec3 origin, std::vector<glm::vec3>& out);

// A binding packed for per-frame float32 evaluation (src/binding/binding_float.cpp): one 16-byte record
// per vertex (face, b1, b2, height as float32) instead of 28 bytes in three arrays, so a frame
// streams 16 bytes in and 12 out per vertex (evaluateBindingFloat: 28 in, 12 out). The
// barycentrics and heights lose what float32 drops (about 1e-7 of a triangle's size and of the
// height), far below the float32 output's own rounding at the garment's size.
struct PackedBindingVertex {
    uint32_t face;
    float b1, b2, height;
};
struct PackedBinding {
    std::vector<PackedBindingVertex> vertices;
};
PackedBinding packBinding(const Binding& binding);

// evaluateBindingFloat on a packed binding (the same float32 kernel, so the same bits): the
// mesh's positions (relative to `origin`) and normals are converted once per call, then every
// vertex is one fused gather, normalize and store.
void evaluatePackedFloat(const PackedBinding& binding, const std::vector<glm::uvec3>& faces,
                         const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                         glm::dvec3 origin, std::vector<glm::vec3>& out);

}  // namespace knit
