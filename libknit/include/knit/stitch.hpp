// knit/stitch.hpp — walk the tiled segments into maximal yarns (closed loops kept).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "knit/pattern.hpp"
#include "knit/tiling.hpp"

namespace knit {

// Yarns in UV space. Yarn y owns vertices [offsets[y], offsets[y+1]); closed[y] marks loops.
struct UvYarns {
    std::vector<glm::dvec2> uv;
    std::vector<double> height;      // metres in object space (pattern z * placement.scale)
    std::vector<double> twist;       // pattern twist angle t
    std::vector<uint32_t> source;    // tiled vertex id = tileSlot * patternVertexCount + local
    std::vector<uint32_t> offsets{0};
    std::vector<uint8_t> closed;

    size_t yarnCount() const { return closed.size(); }
    size_t vertexCount() const { return uv.size(); }
};

// Every tiled vertex appears exactly once. A yarn ends where its next tile is not in the tiling;
// curves entered from their end are reversed. Deterministic for any thread count.
UvYarns stitchYarns(const Pattern& pattern, const PatternAdjacency& adjacency, const Tiling& tiling,
                    const PatternPlacement& placement);

}  // namespace knit
