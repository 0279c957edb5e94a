// garment.hpp — the chart's pattern on a garment (a built-in mesh or an upload), built for the
// page's camera, written as a GLB of yarn centrelines into the server's temporary folder.
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "knit/base_mesh.hpp"
#include "knit/budget.hpp"
#include "knit/pattern.hpp"
#include "knit/tiling.hpp"
#include "knit/view.hpp"

namespace knit::serve {

struct GarmentSettings {
    std::array<double, 2> repeats{0, 0};  // 0 0 and no gauge: the pattern at its own size
    std::optional<Gauge> gauge;
    std::optional<View> view;                    // none: the default framing (knit/view.hpp frameMesh)
    MemoryBudget budget;                         // the scene's stages refuse estimates over it
    uint64_t maxFileBytes = uint64_t(64) << 20;  // the GLB, estimated before it is written
};

// Called between the pipeline's stages (it may throw JobCancelled to stop).
using StageFn = std::function<void(const std::string& stage, int index, int total)>;

// Builds the scene for the view (cells outside the view or facing away are culled; every other
// cell keeps its yarns) and writes its yarn centrelines (line strips with COLOR_0 when the chart
// has colours) to `glbPath`. Returns {"yarns", "points", "bytes", "cells", "culled_cells",
// "repeats": [u, v], "camera": {...}}. Throws knit::Error for what the pipeline refuses and when
// the file would exceed maxFileBytes.
nlohmann::json writeGarmentGlb(const Pattern& pattern, const BaseMesh& mesh, const GarmentSettings& settings,
                               const std::string& glbPath, const StageFn& stage);

}  // namespace knit::serve
