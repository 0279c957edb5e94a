// render_flags.hpp — the render flags of `knit render` (light, mode, image, material, view).
#pragma once
#include <CLI/CLI.hpp>

#include "knit/render.hpp"

namespace knit::cli {

// Registers --light --mode --spp --output --exr --seed --material and the
// material flags (--eta --alpha-along --alpha-across --kR --alpha-tt --kTT --body-albedo
// --reflect-fraction --fiber-count --fiber-twist --fiber-shadow-floor --ply-shadow-floor
// --no-fiber-detail) plus --max-depth --env --light-irradiance --base-mesh --tube-sides (--fov --width --height: view_flags.hpp).
void addRenderFlags(CLI::App& command, RenderOptions& options);

}  // namespace knit::cli
