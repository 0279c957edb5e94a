// The project's own parametric patterns and the registry of built-in names.
#include "knit/generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <sys/stat.h>

#include "knit/chart.hpp"
#include "knit/chart_cache.hpp"
#include "chart/relax_lattice.hpp"
#include "knit/error.hpp"
#include "knit/file_kind.hpp"
#include "util/math.hpp"

namespace knit {

namespace {

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// Throws unless lo <= value <= hi (NaN fails), naming the setting in words and why the range.
void requireWithin(double value, double lo, double hi, const char* setting, const char* unit, const char* why) {
    if (value >= lo && value <= hi) return;
    throw Error("stockinette generator: " + std::string(setting) + " " + number(value) + " is outside " + number(lo) +
                " .. " + number(hi) + " " + unit + ": " + why);
}

// The model's parameters, in model units where one stitch is 2 pi wide, within the shapes the
// model makes a knit of: outside them the pattern was written (exit 0) and was unusable (a cell
// of 1e-33 m, a loop reaching 1e30 stitches sideways).
void checkParams(const StockinetteParams& prm) {
    constexpr double kStitch = util::kTwoPi;
    requireWithin(double(prm.samplesPerStitch), 4, 1e9, "the samples per stitch", "samples",
                  "the loop needs at least 4 samples");
    requireWithin(prm.radius, 1e-6, 1.0, "the generator's yarn radius", "m",
                  "no garment yarn is thinner than a micrometre or thicker than a metre");
    requireWithin(prm.h, kStitch / 16, 16 * kStitch, "the loop height", "model units",
                  "a loop at most 16 times taller or flatter than a stitch is wide");
    const double row = prm.h + prm.rowGap;
    requireWithin(prm.rowGap, prm.h / 4 - prm.h, 16 * kStitch, "the row gap", "model units",
                  "a loop reaches at most 4 rows (row spacing = loop height + row gap) and rows at most 16 stitch "
                  "widths apart");
    requireWithin(prm.a, -kStitch / 2, kStitch / 2, "the loop width", "model units",
                  "the loop legs may bulge at most half a stitch sideways");
    requireWithin(prm.d, -kStitch, kStitch, "the over/under depth", "model units",
                  "the yarn may leave the mid-surface by at most one stitch width");
    requireWithin(prm.modelRadius, 1e-3, std::min(kStitch, row) / 2, "the model yarn radius", "model units",
                  "the yarn must fit within one stitch width and one row spacing (and be more than a "
                  "thousandth of a unit)");
}

}  // namespace

Pattern generateStockinette(const StockinetteParams& prm) {
    checkParams(prm);
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
    if (prm.relax) p.points = impl::restCell(p);
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

std::optional<std::string> chartTextOf(const std::string& fileOrName) {
    if (fileOrName.rfind("chart:", 0) == 0) return builtinChartText(fileOrName);
    if (endsWith(fileOrName, ".chart") || endsWith(fileOrName, ".txt")) return readChartText(fileOrName);
    return std::nullopt;
}

Pattern loadPatternFileOrName(const std::string& fileOrName) {
    struct stat st {};
    const bool exists = stat(fileOrName.c_str(), &st) == 0;
    // Charts: built-in (chart:NAME) or a .chart/.txt file, relaxed on first use and cached.
    if (const std::optional<std::string> chart = chartTextOf(fileOrName)) return cachedChartPattern(*chart, fileOrName);
    if (endsWith(fileOrName, ".json")) return patternFromCurves(loadCurvesJson(fileOrName));
    // A mesh, cache or image read as a .pyp was refused as "a.pc2:1: data before the first block header".
    const std::string kind = fileKind(fileOrName);
    const bool patternKind =
        kind.rfind("a pattern", 0) == 0 || kind.rfind("a chart", 0) == 0 || kind.rfind("a JSON", 0) == 0;
    if (exists && !kind.empty() && !patternKind)
        throw Error("'" + fileOrName + "' is " + kind +
                    ", not a pattern: give a .pyp pattern, a curves .json, a .chart chart or a built-in pattern name");
    if (endsWith(fileOrName, ".pyp") || exists) return loadPyp(fileOrName);
    return builtinPattern(fileOrName);
}

}  // namespace knit
