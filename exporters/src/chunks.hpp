// chunks.hpp (internal) — split curves into chunks for streaming export.
#pragma once
#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

#include <tbb/concurrent_queue.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <glm/vec3.hpp>

#include "knit/polylines.hpp"
#include "knit/sweep.hpp"

namespace knit::impl {

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
void forEachTubeChunk(const Polylines& curves, double radius, const TubeOptions& tube, const std::vector<Chunk>& chunks,
                      const std::function<void(size_t chunkIndex, const TubeMesh& mesh)>& consume);

// Produces chunks 0 .. count-1 in parallel and consumes them in chunk order (a TBB pipeline):
// produce(index, token) fills a reusable Token, consume(index, token) writes it. At most
// min(2 x threads, 8) tokens exist, so memory stays bounded whatever the core count, and what is
// consumed does not depend on the thread count. An exception in either stops the pipeline and
// propagates.
// The chunks orderedChunks keeps in memory at once: min(2 x threads, 8).
inline size_t chunksInFlight() {
    return std::min<size_t>(8, size_t(2 * std::max(1, tbb::this_task_arena::max_concurrency())));
}

template <class Token, class Produce, class Consume>
void orderedChunks(size_t count, Produce produce, Consume consume) {
    struct Slot {
        size_t index = 0;
        Token token;
    };
    const size_t tokens = chunksInFlight();
    std::vector<std::unique_ptr<Slot>> pool;
    tbb::concurrent_queue<Slot*> free;
    for (size_t t = 0; t < tokens; ++t) {
        pool.push_back(std::make_unique<Slot>());
        free.push(pool.back().get());
    }
    size_t next = 0;
    tbb::parallel_pipeline(
        tokens, tbb::make_filter<void, Slot*>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> Slot* {
                    if (next == count) {
                        fc.stop();
                        return nullptr;
                    }
                    // A slot is back in `free` before its token retires, and
                    // at most `tokens` are live: one is always free here.
                    Slot* slot = nullptr;
                    if (!free.try_pop(slot)) throw std::logic_error("orderedChunks: no free slot");
                    slot->index = next++;
                    return slot;
                }) & tbb::make_filter<Slot*, Slot*>(tbb::filter_mode::parallel, [&](Slot* slot) {
                    produce(slot->index, slot->token);
                    return slot;
                }) & tbb::make_filter<Slot*, void>(tbb::filter_mode::serial_in_order, [&](Slot* slot) {
                    consume(slot->index, slot->token);
                    free.push(slot);
                }));
}

}  // namespace knit::impl
