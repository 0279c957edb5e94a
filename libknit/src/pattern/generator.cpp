// The project's own parametric patterns and the registry of built-in names.
#include "knit/generator.hpp"

#include <cmath>
#include <sys/stat.h>

#include "knit/chart.hpp"
#include "knit/chart_cache.hpp"
#include "knit/error.hpp"
#include "util/math.hpp"

namespace knit {

Pattern generateStockinette(const StockinetteParams& prm) {
    if (!(prm.radius > 0) || !(prm.modelRadius > 0) || !(prm.h > 0) || !(prm.rowGap > -prm.h) ||
        prm.samplesPerStitch < 4)
        throw Error(
            "stockinette generator: radius, modelRadius, h must be positive, h + rowGap > 0 and samplesPerStitch >= 4");
    // Before allocating: a point, a twist and an edge per sample, and validation's working copies.
    constexpr double kBytesPerSample = 96;
    prm.budget.require(double(prm.samplesPerStitch) * kBytesPerSample,
                       std::to_string(prm.samplesPerStitch) + " pattern samples", "the samples per stitch");
    const double s = prm.radius / prm.modelRadius;  // metres per model unit
    Pattern p;
    p.name = "stockinette";
    p.px = util::kTwoPi * s;
    p.py = (prm.h + prm.rowGap) * s;
    p.radius = prm.radius;
    const int n = prm.samplesPerStitch;
    // One course per cell: gamma(t) = (t + a sin 2t, h cos t, d cos 2t), t = 2 pi i / n.
    for (int i = 0; i < n; ++i) {
        const double t = util::kTwoPi * i / n;
        p.points.emplace_back((t + prm.a * std::sin(2 * t)) * s, prm.h * std::cos(t) * s, prm.d * std::cos(2 * t) * s);
        p.twist.push_back(0.0);
    }
    // Consecutive samples are joined; the last one continues into the next stitch (+x).
    for (int i = 0; i + 1 < n; ++i) p.edges.push_back({uint32_t(i), uint32_t(i + 1), 0, 0});
    p.edges.push_back({uint32_t(n - 1), 0, 1, 0});
    validatePattern(p, p.name);
    return p;
}

std::vector<std::string> builtinPatternNames() { return {"stockinette"}; }

Pattern builtinPattern(const std::string& name) {
    if (name == "stockinette") return generateStockinette();
    std::string known;
    for (const std::string& n : builtinPatternNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown pattern '" + name + "': not a file and not a built-in pattern (" + known + ")");
}

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

Pattern loadPatternFileOrName(const std::string& fileOrName) {
    struct stat st {};
    const bool exists = stat(fileOrName.c_str(), &st) == 0;
    // Charts: built-in (chart:NAME) or a .chart/.txt file, relaxed on first use and cached.
    if (fileOrName.rfind("chart:", 0) == 0) return cachedChartPattern(builtinChartText(fileOrName), fileOrName);
    if (endsWith(fileOrName, ".chart") || endsWith(fileOrName, ".txt")) {
        return cachedChartPattern(readChartText(fileOrName), fileOrName);
    }
    if (endsWith(fileOrName, ".json")) return patternFromCurves(loadCurvesJson(fileOrName));
    if (endsWith(fileOrName, ".pyp") || exists) return loadPyp(fileOrName);
    return builtinPattern(fileOrName);
}

}  // namespace knit
