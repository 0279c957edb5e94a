// knit/generator.hpp — the project's own parametric patterns (what ships in patterns/).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "knit/budget.hpp"
#include "knit/pattern.hpp"

namespace knit {

// Plain-knit (stockinette) course after K. Crane, "A Simple Parametric Model of Plain-Knit
// Yarns": in model units gamma(t) = (t + a sin 2t, h cos t, d cos 2t), t in [0, 2pi) per stitch,
// one stitch per period, rows spaced h + rowGap apart. The model is scaled so that the yarn
// radius (in model units `modelRadius`) becomes `radius` metres. With `relax` (the default) the
// curve is then brought to rest, period fixed, under the energy the strain tables use
// (knit/strain.hpp: nearly inextensible yarn, bending, contact): the model's yarns press 0.16
// radii into each other, and a pattern that is not at rest under that energy moves when it is
// strained by nothing but its own tension.
struct StockinetteParams {
    double a = 1.5;            // loop width (sideways bulge of the loop legs)
    double h = 4.0;            // loop height
    double d = 1.0;            // over/under depth (height above/below the mid-surface)
    double rowGap = 0.5;       // extra row spacing: period y = h + rowGap
    double modelRadius = 0.8;  // yarn radius in model units (0.8 gives a snug fit)
    double radius = 0.001;     // yarn radius in metres
    int samplesPerStitch = 24;
    bool relax = true;  // false: the model's curve as it is
    // The pattern's memory (from samplesPerStitch) is checked against it before allocating.
    MemoryBudget budget;
};

Pattern generateStockinette(const StockinetteParams& params = {});

// Names of the built-in patterns ("stockinette", ...).
std::vector<std::string> builtinPatternNames();
// Built-in pattern by name; throws knit::Error for an unknown name.
Pattern builtinPattern(const std::string& name);
// A pattern from a file (.pyp or .json curves) or a built-in name.
Pattern loadPatternFileOrName(const std::string& fileOrName);
// The chart text loadPatternFileOrName relaxes for `fileOrName` (chart:NAME, a .chart or .txt
// file; knit::Error as there when it cannot be read), nothing for any other pattern.
std::optional<std::string> chartTextOf(const std::string& fileOrName);

}  // namespace knit
