// yarnRegion (knit/detail.hpp): the cells a view builds yarns for, the ply- and yarn-level cells
// grown by a ring of neighbours.
#include <algorithm>

#include "knit/detail.hpp"
#include "knit/error.hpp"

namespace knit {

std::vector<glm::ivec2> yarnRegion(const CellLevels& levels, int ring) {
    if (levels.cells.size() != levels.level.size())
        throw Error("cannot build the view: " + std::to_string(levels.level.size()) + " levels for " +
                    std::to_string(levels.cells.size()) + " cells");
    if (ring < 0) throw Error("cannot build the view: the region's ring of cells must not be negative");
    std::vector<glm::ivec2> out;
    for (size_t k = 0; k < levels.cells.size(); ++k) {
        if (levels.level[k] != DetailLevel::Plies && levels.level[k] != DetailLevel::Yarns) continue;
        for (int dy = -ring; dy <= ring; ++dy)
            for (int dx = -ring; dx <= ring; ++dx) out.push_back(levels.cells[k] + glm::ivec2(dx, dy));
    }
    // Row-major (by j, then i), each cell once.
    std::sort(out.begin(), out.end(), [](glm::ivec2 a, glm::ivec2 b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace knit
