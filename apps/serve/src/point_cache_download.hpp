// point_cache_download.hpp — the garment's yarn centrelines as a one-frame PC2 point cache
// (knit/cache.hpp), the points in the order of the yarns, for tools that read point caches.
#pragma once
#include <string>

#include "garment.hpp"
#include "temp_folder.hpp"

namespace knit::serve {

// The PC2 bytes (written in `temp` and removed). Throws knit::Error for what the pipeline
// refuses and when the file would exceed settings.maxFileBytes.
std::string yarnPointCache(const Pattern& pattern, const BaseMesh& mesh, const GarmentSettings& settings,
                           TempFolder& temp);

}  // namespace knit::serve
