// scene_checks.hpp (internal) — the choice of curves exportScene() and checkSceneExport() share.
#pragma once
#include "knit/export.hpp"

namespace knit::impl {

// True when `options` write the plies of `scene` (built, or generated while writing): ply curves,
// or tubes of plies (TubeSource::Auto: when the scene has plies).
bool exportsPlies(const Scene& scene, const ExportOptions& options);

}  // namespace knit::impl
