// report.hpp — what the commands write besides their main output: JSON reports (--report) and
// notes on stderr.
#pragma once
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "knit/scene.hpp"

namespace knit::cli {

// The check `build` and `render` make before any work: a --report path (if given) whose folder
// exists and is writable and that is not a folder; throws knit::Error naming it.
void checkReportPath(const std::string& path);

// Writes `report` (indented, newline-terminated) to `path` atomically.
void writeReport(const std::string& path, const nlohmann::json& report);

// The `knit build` report of a scene: pattern, mesh, placement, and its statistics (counts,
// vertices per level, segment lengths, stage times).
nlohmann::json sceneReport(const Scene& scene, const SceneStats& stats);
// Why the scene deforms as it does, in the command line's words (the reports' deform.why).
std::string deformWhy(const DeformOptions& deform);

// What the user should know about a built scene that is not an error (stderr): overlapping
// UV charts.
void printWarnings(const Scene& scene);

}  // namespace knit::cli
