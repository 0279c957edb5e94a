// render_report.hpp — the JSON of `knit render` (printed on stdout, and the --report file).
#pragma once
#include <nlohmann/json.hpp>

#include "knit/render.hpp"

namespace knit::cli {

// Time, rays/s, peak memory and scene memory, and the settings (mode, light, size, spp, the
// resolved material, the files written) of a render as JSON.
nlohmann::json renderReport(const RenderResult& result);

}  // namespace knit::cli
