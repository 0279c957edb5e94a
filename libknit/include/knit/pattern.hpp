// knit/pattern.hpp — one periodic cell of yarn: the input of the whole pipeline.
//
// Two input forms:
//  * .pyp (Leaf et al. 2018 / HYLC / MADYPG): vertices plus explicit periodic edges.
//  * curves-only JSON: open curves inside one cell plus the period; the periodic edges are
//    re-derived with the partner-endpoint search of Montazeri et al. 2021 (patternFromCurves).
#pragma once
#include <array>
#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace knit {

// Edge from vertex v0 in tile (i, j) to vertex v1 in tile (i + dx, j + dy); |dx| + |dy| <= 1.
// i counts periods along x (pattern x -> u), j along y (pattern y -> v).
struct PeriodicEdge {
    uint32_t v0 = 0, v1 = 0;
    int32_t dx = 0, dy = 0;
    bool operator==(const PeriodicEdge& o) const { return v0 == o.v0 && v1 == o.v1 && dx == o.dx && dy == o.dy; }
};

struct Pattern {
    std::string name;                // file name or generator name, for messages
    double px = 0, py = 0;           // period (metres)
    double radius = 0;               // yarn radius (metres)
    std::vector<glm::dvec3> points;  // x, y in the plane, z = height above the mid-surface (metres)
    std::vector<double> twist;       // per-vertex twist angle t (radians), same size as points
    std::vector<PeriodicEdge> edges;
    // Stitch columns and rows in one period (the optional *GAUGE block "stitches rows"; a chart
    // records its size). Files without the block: one period is one stitch column by one row.
    int stitchesPerPeriod = 1, rowsPerPeriod = 1;
    // Optional per-vertex yarn colour, linear RGB in [0, 1] (the optional *RGB block "r g b", one
    // row per vertex; a chart's colour layer). Empty: no colour, and nothing downstream carries any.
    std::vector<glm::vec3> colour;
    // Optional simulation blocks (*RL, *RK, *RT, *RefD1, *RefT, ...), kept verbatim by name.
    std::map<std::string, std::vector<std::vector<double>>> extraBlocks;
};

// Parses .pyp text. `source` names the input in error messages ("file.pyp:LINE: what").
// Throws knit::Error on malformed input (missing block, wrong counts, NaN/Inf, edge to a missing
// vertex, |dx|+|dy| > 1, non-positive period or radius, a vertex of degree > 2).
Pattern parsePyp(std::istream& in, const std::string& source);
Pattern loadPyp(const std::string& path);
void writePyp(std::ostream& out, const Pattern& pattern);

// Checks the invariants every stage relies on; throws knit::Error naming the element.
void validatePattern(const Pattern& pattern, const std::string& source);

// ---- curves-only form ----------------------------------------------------------------------
// JSON: {"period": [px, py], "radius": r, "curves": [[[x,y,z], ...], ...]} (metres).
struct CurveCell {
    std::string name;
    double px = 0, py = 0, radius = 0;
    std::vector<std::vector<glm::dvec3>> curves;  // open curves inside one cell
};

CurveCell parseCurvesJson(const std::string& text, const std::string& source);
CurveCell loadCurvesJson(const std::string& path);
std::string curvesToJson(const CurveCell& cell);

struct PartnerOptions {
    // An endpoint's partner must lie within this distance (in yarn radii) of the endpoint's
    // expected continuation; farther is an error naming the endpoint.
    double tolerance = 1.0;
};

// The paper's partner-endpoint search: every curve endpoint is joined to the closest endpoint
// of a curve in one of the four neighbouring translated cells. Partners are symmetric.
// Throws knit::Error naming an endpoint without a partner within tolerance.
Pattern patternFromCurves(const CurveCell& cell, const PartnerOptions& options = {});

// Splits a pattern at its periodic edges (dx, dy) != (0, 0) into open curves in one cell;
// the inverse of patternFromCurves (tests check the round trip gives back the same edges).
// originalVertex (optional) receives, for each curve point in order, its pattern vertex index.
CurveCell splitAtPeriodicEdges(const Pattern& pattern, std::vector<uint32_t>* originalVertex = nullptr);

// ---- topology of the periodic pattern -------------------------------------------------------
// Up to two neighbours per pattern vertex, as (vertex, tile offset). Undirected.
struct PatternNeighbor {
    int32_t v = -1;  // -1: no neighbour in this slot
    int32_t dx = 0, dy = 0;
};
struct PatternAdjacency {
    std::vector<std::array<PatternNeighbor, 2>> slots;  // per vertex
};
// Throws knit::Error when a vertex has degree > 2.
PatternAdjacency buildAdjacency(const Pattern& pattern);

struct PatternInfo {
    double px = 0, py = 0, radius = 0;
    size_t vertexCount = 0, edgeCount = 0;
    // Edges crossing each side of the cell: +x, -x, +y, -y (each crossing edge counted once,
    // on the side it leaves through from v0).
    std::array<size_t, 4> crossings{};
    // Closed loops and open yarns of a 1x1 periodic tiling (the pattern on a torus).
    size_t loops1x1 = 0;
    size_t openYarns1x1 = 0;
    glm::dvec3 boundsMin{0.0}, boundsMax{0.0};
};
PatternInfo describePattern(const Pattern& pattern);

}  // namespace knit
