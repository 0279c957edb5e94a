// empty_result.hpp — refuses an export that would hold no curves (a pattern without edges, repeats
// so small that no yarn lands on the mesh, a ply pitch longer than every yarn), saying why
// nothing was made, before any file is written.
#pragma once
#include "knit/export.hpp"
#include "knit/scene.hpp"

namespace knit::cli {

// Throws knit::Error "nothing to export: <why>; no file written" when `options` would write no
// curve of `scene`.
void refuseEmptyExport(const Scene& scene, const ExportOptions& options);

}  // namespace knit::cli
