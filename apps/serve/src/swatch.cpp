// The swatch: the pattern at its own size on a square of the built-in plane (swatch.hpp).
#include "swatch.hpp"

#include <algorithm>
#include <cmath>

#include "knit/scene.hpp"

namespace knit::serve {
namespace {

constexpr double kPointsPerMetre = 1e6, kColourSteps = 1e3;

// Integers: the JSON library writes a double with 17 digits (0.026669 as 0.026669000000000002), so
// points in metres rounded to a micrometre took about twice the bytes of micrometres.
long rounded(double x, double scale) { return std::lround(x * scale); }

nlohmann::json curvesJson(const MappedYarns& yarns) {
    nlohmann::json curves = nlohmann::json::array();
    const Polylines& c = yarns.curves;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        std::vector<long> points, colours;
        points.reserve(3 * c.size(k));
        for (uint32_t i = c.begin(k); i < c.end(k); ++i)
            for (int a = 0; a < 3; ++a) points.push_back(rounded(c.points[i][a], kPointsPerMetre));
        nlohmann::json curve = {{"closed", c.isClosed(k)}, {"points", points}};
        if (!yarns.colour.empty()) {
            for (uint32_t i = c.begin(k); i < c.end(k); ++i)
                for (int a = 0; a < 3; ++a) colours.push_back(rounded(yarns.colour[i][a], kColourSteps));
            curve["colours"] = colours;
        }
        curves.push_back(std::move(curve));
    }
    return curves;
}

}  // namespace

nlohmann::json swatchJson(const Pattern& pattern, std::array<double, 2> repeats) {
    if (repeats[0] == 0 && repeats[1] == 0) {
        repeats[0] = std::ceil(12.0 / std::max(pattern.stitchesPerPeriod, 1));
        repeats[1] = std::ceil(12.0 / std::max(pattern.rowsPerPeriod, 1));
    }
    // A square plane as wide as the longer side, the pattern at its own size on it (the placement's
    // physical size): stitches keep their shape, the shorter side gets part tiles.
    ProceduralMeshOptions plane;
    plane.size = std::max(repeats[0] * pattern.px, repeats[1] * pattern.py);
    plane.resU = plane.resV = 8;
    SceneOptions options;
    options.buildPlies = false;
    options.placement.repeats = {0.0, 0.0};
    const Scene scene = buildScene(pattern, makePlane(plane), options);
    return {{"yarns", scene.yarns().curves.curveCount()},
            {"radius", scene.yarnRadius()},
            {"size", plane.size},
            {"point_unit", 1 / kPointsPerMetre},
            {"colour_unit", 1 / kColourSteps},
            {"curves", curvesJson(scene.yarns())}};
}

}  // namespace knit::serve
