// swatch.hpp — a relaxed chart knitted into a small square swatch (the built-in plane, the
// pattern at its own size) and its yarns as JSON for the page's 3D view.
#pragma once
#include <array>

#include <nlohmann/json.hpp>

#include "knit/pattern.hpp"

namespace knit::serve {

// The swatch's yarns: {"yarns": N, "radius": r, "size": side (m), "point_unit": 1e-6,
// "colour_unit": 1e-3, "curves": [{"closed": bool, "points": [x, y, z, ...], "colours": [r, g, b,
// ...] (linear, only with a colour layer)}]}, points and colours integers in their units (metres
// for the points). `repeats` 0 0: enough periods for about 12 stitches and rows each way. Points
// are on the plane y = 0 (its normal +y).
nlohmann::json swatchJson(const Pattern& pattern, std::array<double, 2> repeats);

}  // namespace knit::serve
