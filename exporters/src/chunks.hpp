// chunks.hpp (internal) — split curves into chunks for streaming export.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/polylines.hpp"
#include "knit/sweep.hpp"

namespace knit::detail {

// Consecutive curves [firstCurve, lastCurve) holding `vertices` output vertices.
struct Chunk {
    size_t firstCurve = 0;
    size_t lastCurve = 0;
    size_t vertices = 0;   // tube vertices (tubes) or curve points (curves)
    size_t triangles = 0;  // tube triangles (tubes)
};

// Greedy: consecutive curves until the next one would exceed `maxVertices` (a single larger
// curve gets a chunk of its own). Curves producing nothing (< 2 points) are still covered.
std::vector<Chunk> planTubeChunks(const Polylines& curves, const TubeOptions& tube, size_t maxVertices);
std::vector<Chunk> planCurveChunks(const Polylines& curves, size_t maxPoints);

// Centre of the bounding box of the chunk's points (double): the chunk's local origin.
glm::dvec3 chunkOrigin(const Polylines& curves, const Chunk& chunk);

// Sweeps each chunk into one reused mesh and hands it to `consume`: at most one chunk mesh in
// memory, allocated once.
void forEachTubeChunk(const Polylines& curves, double radius, const TubeOptions& tube,
                      const std::vector<Chunk>& chunks,
                      const std::function<void(size_t chunkIndex, const TubeMesh& mesh)>& consume);

}  // namespace knit::detail
