// knit/trace_mode.hpp — the tracer's geometry modes and what the scene of one costs (no Embree
// here: the Embree scene itself is internal to render_check, see src/tracing/trace_scene.hpp).
//
// Modes (all three model the same solid: every ply a tube of the ply radius around its polyline,
// round ends):
//   Curves: Embree's round linear curves over the ply segments.
//   Tubes:  the exporter's swept tube meshes with hemispherical end caps.
//   Grid:   the two-stage idea: one Embree user primitive per non-empty UV-grid cell, whose
//           callback intersects only that cell's ply segments.
#pragma once
#include <cstdint>
#include <string>

namespace knit {

enum class GeometryMode { Curves, Tubes, Grid };
const char* modeName(GeometryMode mode);
GeometryMode parseMode(const std::string& name);  // throws knit::Error

struct TraceMemory {
    int64_t embreeBytes = 0;    // BVH and primitive data allocated by Embree for this scene
    int64_t geometryBytes = 0;  // our buffers needed to intersect (vertices, indices, cells)
    int64_t shadingBytes = 0;   // per-point shading attributes (same for every mode)
    int64_t sceneBytes() const { return embreeBytes + geometryBytes; }
};

}  // namespace knit
