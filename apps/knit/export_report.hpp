// export_report.hpp — the "export" part of `knit build --report`.
#pragma once
#include <nlohmann/json.hpp>

#include "knit/export.hpp"

namespace knit::cli {

// Counts, bytes, chunks, peak memory and time of an export as JSON; the mesh byte counts and
// the compression ratio only when tube meshes were written.
nlohmann::json exportReport(const ExportStats& stats);

}  // namespace knit::cli
