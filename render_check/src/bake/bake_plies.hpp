// bake_plies.hpp — internal: the plies of the tiles around one pattern cell, flat in z = 0, with
// each yarn's ply pitch adjusted so that its plies repeat with the pattern (bake.hpp).
#pragma once
#include <vector>

#include "knit/pattern.hpp"
#include "knit/plies.hpp"

namespace knit {

struct BakePlies {
    Plies plies;
    std::vector<double> yarnPitch;  // per yarn: the pitch its plies were made with (metres)
    double yarnRadius = 0;          // resolved (metres)
    double zMin = 0, zMax = 0;      // extent of the yarn solids along z (pattern heights -+ radius)
};

// Tiles: tileReach(pattern) plus one tile on every side and a second one towards +x and +y (so at
// least 4 x 4: the cell of any BakeOptions::origin sees its neighbours).
// `margin` more tiles on every side (oblique rays of the scattering table cross several tiles).
// options.yarnRadius 0 = pattern.radius. periodicPitch off: every yarn gets options.pitch.
BakePlies bakePlies(const Pattern& pattern, const PlyOptions& options, bool periodicPitch, int margin = 0);

}  // namespace knit
