// uv_folds.hpp (internal) — UV islands that fold over themselves: which triangles lie on the
// folded-over side of an island (see buildUvGrid, UvGrid::foldedUvFaces).
#pragma once
#include <cstdint>
#include <vector>

#include "knit/base_mesh.hpp"

namespace knit::impl {

// Two faces sharing a UV edge; `folded` when both lie on the same side of it in UV (the island
// folds over that edge instead of continuing across it).
struct UvEdgeLink {
    uint32_t f = 0, g = 0;
    bool folded = false;
};

struct UvFolds {
    size_t faces = 0;                 // faces on the folded-over side of their island
    uint32_t example = UINT32_MAX;    // the lowest-numbered of them
    std::vector<uint32_t> perIsland;  // folded faces per island
};

// Each island's faces get a side by walking its UV edges from its lowest face: crossing a folded
// edge changes side. The side with the smaller UV area is the folded-over one. Faces of zero UV
// area belong to no side.
UvFolds findUvFolds(const BaseMesh& mesh, const std::vector<uint32_t>& islandOfFace, uint32_t islandCount,
                    const std::vector<int8_t>& faceOrientation, const std::vector<UvEdgeLink>& links);

}  // namespace knit::impl
