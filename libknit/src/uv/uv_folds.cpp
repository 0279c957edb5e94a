// uv_folds.cpp — the folded-over side of each UV island (see uv_folds.hpp).
#include "uv_folds.hpp"
#include "util/csr.hpp"

#include <cmath>

namespace knit::impl {
namespace {

double uvArea(const BaseMesh& mesh, size_t f) {
    const glm::uvec3 t = mesh.faceUvs[f];
    const glm::dvec2 a = mesh.uvs[t.x], b = mesh.uvs[t.y], c = mesh.uvs[t.z];
    return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// Per face its linked faces and whether the link is folded, as offsets into one list.
struct LinkLists {
    std::vector<uint32_t> offsets, other;
    std::vector<char> folded;
};

LinkLists linkLists(size_t faces, const std::vector<UvEdgeLink>& links) {
    LinkLists l;
    l.offsets.assign(faces + 1, 0);
    for (const UvEdgeLink& k : links) ++l.offsets[k.f + 1], ++l.offsets[k.g + 1];
    util::countsToOffsets(l.offsets);
    l.other.resize(2 * links.size());
    l.folded.resize(2 * links.size());
    std::vector<uint32_t> fill(l.offsets.begin(), l.offsets.end() - 1);
    for (const UvEdgeLink& k : links) {
        l.other[fill[k.f]] = k.g, l.folded[fill[k.f]++] = k.folded;
        l.other[fill[k.g]] = k.f, l.folded[fill[k.g]++] = k.folded;
    }
    return l;
}

}  // namespace

UvFolds findUvFolds(const BaseMesh& mesh, const std::vector<uint32_t>& islandOfFace, uint32_t islandCount,
                    const std::vector<int8_t>& faceOrientation, const std::vector<UvEdgeLink>& links) {
    UvFolds folds;
    folds.perIsland.assign(islandCount, 0);
    bool anyFold = false;
    for (const UvEdgeLink& k : links) anyFold = anyFold || k.folded;
    if (!anyFold) return folds;
    // Step 1: sides by a breadth-first walk from each island's lowest face.
    const size_t nf = islandOfFace.size();
    const LinkLists l = linkLists(nf, links);
    std::vector<int8_t> side(nf, -1);
    std::vector<double> area(2 * size_t(islandCount), 0.0);  // per island: side 0, side 1
    std::vector<uint32_t> queue;
    for (uint32_t start = 0; start < nf; ++start) {
        if (side[start] >= 0 || faceOrientation[start] == 0) continue;
        side[start] = 0;
        queue.assign(1, start);
        for (size_t q = 0; q < queue.size(); ++q) {
            const uint32_t f = queue[q];
            area[2 * size_t(islandOfFace[f]) + size_t(side[f])] += uvArea(mesh, f);
            for (uint32_t i = l.offsets[f]; i < l.offsets[f + 1]; ++i)
                if (side[l.other[i]] < 0) {
                    side[l.other[i]] = int8_t(side[f] ^ l.folded[i]);
                    queue.push_back(l.other[i]);
                }
        }
    }
    // Step 2: the smaller side of each island is folded over (a tie: the side away from its lowest face).
    for (uint32_t f = 0; f < nf; ++f) {
        if (side[f] < 0) continue;
        const size_t c = islandOfFace[f];
        const int8_t smaller = area[2 * c + 1] <= area[2 * c] ? 1 : 0;
        if (side[f] != smaller) continue;
        ++folds.faces;
        ++folds.perIsland[c];
        if (folds.example == UINT32_MAX) folds.example = f;
    }
    return folds;
}

}  // namespace knit::impl
