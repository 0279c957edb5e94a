// knit/stitch.hpp — walk the tiled segments into maximal yarns (closed loops kept).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/pattern.hpp"
#include "knit/tiling.hpp"

namespace knit {

// The pattern neighbour beyond an open yarn's end whose tile was not generated (it lies outside
// the cells the mesh covers): binding treats it like a cut vertex, so the yarn ends exactly where
// it crosses the UV boundary and can be welded across seams.
struct GhostVertex {
    bool present = false;
    glm::dvec2 uv{0.0};
    double height = 0, twist = 0;
};

// Yarns in UV space. Yarn y owns vertices [offsets[y], offsets[y+1]); closed[y] marks loops.
struct UvYarns {
    std::vector<glm::dvec2> uv;
    std::vector<double> height;     // metres in object space (pattern z * placement.scale)
    std::vector<double> twist;      // pattern twist angle t
    std::vector<uint32_t> source;   // tiled vertex id = tileSlot * patternVertexCount + local
    std::vector<glm::vec3> colour;  // linear yarn colour per vertex; empty when the pattern has none
    std::vector<uint32_t> offsets{0};
    std::vector<uint8_t> closed;
    std::vector<std::array<GhostVertex, 2>> ghosts;  // per yarn: beyond its first / last vertex
    // Per yarn: the only UV island binding may place it on (empty: any island). Set when UV islands
    // overlap and each island is tiled on its own; `source` then counts within the island's tiling.
    std::vector<uint32_t> island;

    size_t yarnCount() const { return closed.size(); }
    size_t vertexCount() const { return uv.size(); }
};

// Which of the stitched yarns to keep (level of detail: only the yarns through a view's region).
// Only the yarns with a vertex in a kept tile are walked, each from the start the unfiltered walk
// takes (an open yarn from its end of lower id, a loop from its lowest id) and in its order, so
// every kept yarn is the one the unfiltered stitch makes, vertex for vertex, and the other tiles
// are never visited.
struct StitchFilter {
    std::vector<uint8_t> keepTile;  // per tile slot of the tiling: 1 = keep every yarn through it
    // Called with the kept vertex count before their data is allocated (a memory check may throw).
    std::function<void(uint64_t keptVertices)> beforeAllocate;
};

// Every tiled vertex appears exactly once (without a filter). A yarn ends where its next tile is
// not in the tiling; curves entered from their end are reversed. Deterministic for any thread
// count.
UvYarns stitchYarns(const Pattern& pattern, const PatternAdjacency& adjacency, const Tiling& tiling,
                    const PatternPlacement& placement, const StitchFilter* filter = nullptr);

// Appends the yarns of `more` (tiled for `island`) to `yarns`, restricted to that island.
void appendIslandYarns(UvYarns& yarns, const UvYarns& more, uint32_t island);

}  // namespace knit
