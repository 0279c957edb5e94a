// export_budget.hpp (internal) — the memory of a tube export, estimated before the first chunk is
// swept and checked against ExportOptions::budget.
#pragma once
#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit::impl {

// Tube meshes: the largest chunk (options.chunkVertices, or a longer curve's own chunk) times the
// chunks in memory at once (glTF sweeps and encodes in parallel; other formats one at a time),
// plus Draco's encoder per chunk. Driven by --sides, --chunk-vertices and --draco-bits.
// `options.chunkVertices` must be resolved (not 0).
void checkTubeExportBudget(const Polylines& curves, const TubeOptions& tube, const ExportOptions& options, bool gltf);

// Ply curves generated chunk by chunk (a glTF export of plies not built with the scene): `total`
// ply points in all, `largestChunk` in the largest chunk (a yarn's plies are never split), the
// chunks in memory at once of that size at most. Driven by the ply pitch and the samples per turn.
void checkStreamedPlyBudget(size_t total, size_t largestChunk, const ExportOptions& options);

}  // namespace knit::impl
