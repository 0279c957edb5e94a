// render_budget.hpp (internal) — the memory of a render, estimated from its counts before the
// image and the geometry are allocated and checked against RenderOptions::budget.
#pragma once
#include "knit/plies.hpp"
#include "knit/render.hpp"

namespace knit::impl {

// The image (width x height; driven by --width / --height) and the geometry of the mode over the
// plies' segments (curves, grid; tubes: triangles of tubeSides, driven by --tube-sides).
void checkRenderBudget(const Plies& plies, const RenderOptions& options);

}  // namespace knit::impl
