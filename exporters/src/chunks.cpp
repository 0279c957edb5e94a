// chunks.cpp — chunk planning and chunk-by-chunk tube sweeping (streaming export).
#include "chunks.hpp"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>

namespace knit::impl {

namespace {

template <class CountFn>
std::vector<Chunk> planChunks(const Polylines& curves, size_t maxVertices, CountFn count) {
    std::vector<Chunk> chunks;
    Chunk cur;
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const auto [v, t] = count(c);
        if (cur.lastCurve > cur.firstCurve && cur.vertices > 0 && cur.vertices + v > maxVertices) {
            chunks.push_back(cur);
            cur = Chunk{c, c, 0, 0};
        }
        cur.lastCurve = c + 1;
        cur.vertices += v;
        cur.triangles += t;
    }
    if (cur.lastCurve > cur.firstCurve) chunks.push_back(cur);
    return chunks;
}

}  // namespace

std::vector<Chunk> planTubeChunks(const Polylines& curves, const TubeOptions& tube, size_t maxVertices) {
    return planChunks(curves, std::max<size_t>(maxVertices, 1), [&](size_t c) {
        const uint32_t n = curves.size(c);
        const bool closed = curves.isClosed(c);
        return std::pair<size_t, size_t>(tubeVertexCount(n, closed, tube), tubeTriangleCount(n, closed, tube));
    });
}

std::vector<Chunk> planCurveChunks(const Polylines& curves, size_t maxPoints) {
    return planChunks(curves, std::max<size_t>(maxPoints, 1), [&](size_t c) {
        const uint32_t n = curves.size(c);
        return std::pair<size_t, size_t>(n >= 2 ? n : 0, 0);
    });
}

glm::dvec3 chunkOrigin(const Polylines& curves, const Chunk& chunk) {
    const uint32_t b = curves.begin(chunk.firstCurve), e = curves.end(chunk.lastCurve - 1);
    if (b == e) return glm::dvec3(0.0);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (uint32_t i = b; i < e; ++i) {
        lo = glm::min(lo, curves.points[i]);
        hi = glm::max(hi, curves.points[i]);
    }
    return 0.5 * (lo + hi);
}

void forEachTubeChunk(const Polylines& curves, double radius, const TubeOptions& tube, const std::vector<Chunk>& chunks,
                      const std::function<void(size_t chunkIndex, const TubeMesh& mesh)>& consume) {
    // One mesh reused for every chunk: at most one chunk's tube mesh is alive, and its memory
    // is allocated (and page-faulted) once instead of once per chunk.
    TubeMesh mesh;
    for (size_t k = 0; k < chunks.size(); ++k) {
        sweepTubes(curves, radius, tube, chunks[k].firstCurve, chunks[k].lastCurve, chunkOrigin(curves, chunks[k]),
                   mesh);
        consume(k, mesh);
    }
}

}  // namespace knit::impl
