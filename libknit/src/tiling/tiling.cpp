// Pattern placement in UV space and the set of tiles a mesh needs.
#include "knit/tiling.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"

namespace knit {

namespace {

[[noreturn]] void badGauge(const std::string& text, const std::string& what) {
    throw Error("the gauge '" + text + "': " + what +
                " (expected STITCHES x ROWS / LENGTH with a unit mm, cm, m or in, e.g. 22x30/10cm)");
}

// A positive finite number filling all of `token`; `what` names it in the error.
double gaugeNumber(const std::string& text, const std::string& token, const std::string& what) {
    const char* begin = token.c_str();
    char* end = nullptr;
    const double value = token.empty() ? 0.0 : std::strtod(begin, &end);
    if (token.empty() || end == begin || *end != '\0') badGauge(text, what + " '" + token + "' is not a number");
    if (!util::positiveFinite(value)) badGauge(text, what + " '" + token + "' must be positive and finite");
    return value;
}

// Metres per unit of a gauge length, 0 for an unknown unit.
double metresPerUnit(const std::string& unit) {
    if (unit == "mm") return 0.001;
    if (unit == "cm") return 0.01;
    if (unit == "m") return 1.0;
    if (unit == "in") return 0.0254;
    return 0.0;
}

// Repeats that give one period the gauge's size: stitchesPerPeriod stitches by rowsPerPeriod rows.
glm::dvec2 gaugeRepeats(const Pattern& pattern, const Gauge& g, glm::dvec2 metresPerUv) {
    const glm::dvec2 periodMetres(pattern.stitchesPerPeriod * g.length / g.stitches,
                                  pattern.rowsPerPeriod * g.length / g.rows);
    return metresPerUv / periodMetres;
}

}  // namespace

Gauge parseGauge(const std::string& text) {
    // Step 1: drop blanks, split at 'x' and '/'.
    std::string t;
    for (const char c : text)
        if (!std::isspace(static_cast<unsigned char>(c))) t += c;
    const size_t slash = t.find('/');
    if (slash == std::string::npos) badGauge(text, "no '/' before the length");
    const size_t cross = t.find_first_of("xX");
    if (cross == std::string::npos || cross > slash) badGauge(text, "no 'x' between stitches and rows");
    // Step 2: the length's unit is its trailing letters.
    const std::string lengthText = t.substr(slash + 1);
    size_t unitAt = lengthText.size();
    while (unitAt > 0 && std::isalpha(static_cast<unsigned char>(lengthText[unitAt - 1]))) --unitAt;
    const std::string unit = lengthText.substr(unitAt);
    if (unit.empty()) badGauge(text, "the length has no unit");
    const double perUnit = metresPerUnit(unit);
    if (perUnit == 0.0) badGauge(text, "unknown length unit '" + unit + "'");
    // Step 3: the three numbers.
    Gauge g;
    g.stitches = gaugeNumber(text, t.substr(0, cross), "stitches");
    g.rows = gaugeNumber(text, t.substr(cross + 1, slash - cross - 1), "rows");
    g.length = gaugeNumber(text, lengthText.substr(0, unitAt), "length") * perUnit;
    return g;
}

PatternPlacement placePattern(const Pattern& pattern, const BaseMesh& mesh, const PlacementOptions& options) {
    // Step 1: the options: repeats, or a gauge, or neither (physical size).
    const glm::dvec2 r = options.repeats;
    const bool physical = r.x == 0.0 && r.y == 0.0;
    if (!physical && !util::positiveFinite(r)) {
        std::ostringstream msg;
        msg << "repeats (" << r.x << ", " << r.y
            << ") must both be positive (or both 0 for the pattern's physical size)";
        throw Error(msg.str());
    }
    if (options.gauge && !physical)
        throw Error("the gauge and the repeats are mutually exclusive (a gauge sets the repeats)");
    if (options.gauge && !(util::positiveFinite(options.gauge->stitches) && util::positiveFinite(options.gauge->rows) &&
                           util::positiveFinite(options.gauge->length)))
        throw Error("the gauge: stitches, rows and length must be positive and finite");
    // Step 2: the mesh's own size and the repeats.
    const glm::dvec2 metresPerUv = uvToMetreScale(mesh);
    if (!(metresPerUv.x > 0 && metresPerUv.y > 0))
        throw Error(mesh.name +
                    ": cannot place the pattern: the mesh has no triangle with non-degenerate UVs and 3D area");
    PatternPlacement placement;
    placement.repeats = options.gauge ? gaugeRepeats(pattern, *options.gauge, metresPerUv)
                        : physical    ? metresPerUv / glm::dvec2(pattern.px, pattern.py)
                                      : r;
    if (placement.repeats.x > 1e7 || placement.repeats.y > 1e7) {
        std::ostringstream msg;
        if (physical && !options.gauge)
            msg << pattern.name << ": at its physical size (period " << pattern.px << " x " << pattern.py
                << " m) on mesh '" << mesh.name << "' (" << metresPerUv.x << " x " << metresPerUv.y
                << " m per UV unit) the pattern repeats " << placement.repeats.x << " x " << placement.repeats.y
                << " times per UV unit, beyond 1e7: the period or the mesh's size is far outside any garment; "
                   "check their units, or set the repeats";
        else
            msg << (options.gauge ? "the gauge gives the repeats (" : "the repeats (") << placement.repeats.x << ", "
                << placement.repeats.y << (options.gauge ? "), beyond" : ") are beyond") << " 1e7 periods per UV unit";
        throw Error(msg.str());
    }
    // Step 3: physical size of one period on the mesh relative to the pattern's own period.
    placement.periodMetres = metresPerUv / placement.repeats;
    const double sx = metresPerUv.x / (placement.repeats.x * pattern.px);
    const double sy = metresPerUv.y / (placement.repeats.y * pattern.py);
    placement.scale = std::sqrt(sx * sy);
    return placement;
}

namespace {

Tiling tilingFromMarks(glm::ivec2 minTile, glm::ivec2 dims, std::vector<int32_t> marks) {
    Tiling t;
    t.minTile = minTile;
    t.dims = dims;
    t.tileSlot = std::move(marks);
    for (int32_t y = 0; y < dims.y; ++y)
        for (int32_t x = 0; x < dims.x; ++x) {
            int32_t& slot = t.tileSlot[size_t(y) * size_t(dims.x) + size_t(x)];
            if (slot < 0) continue;
            slot = int32_t(t.tiles.size());
            t.tiles.push_back(minTile + glm::ivec2(x, y));
        }
    return t;
}

}  // namespace

TileReach tileReach(const Pattern& pattern, glm::dvec2 margin) {
    if (!(margin.x >= 0 && margin.x <= pattern.px)) margin.x = margin.x > pattern.px ? pattern.px : 0.0;
    if (!(margin.y >= 0 && margin.y <= pattern.py)) margin.y = margin.y > pattern.py ? pattern.py : 0.0;
    glm::ivec2 lo(INT32_MAX), hi(INT32_MIN);
    for (const glm::dvec3& q : pattern.points) {
        const glm::ivec2 c0(int32_t(std::floor((q.x - margin.x) / pattern.px)),
                            int32_t(std::floor((q.y - margin.y) / pattern.py)));
        const glm::ivec2 c1(int32_t(std::floor((q.x + margin.x) / pattern.px)),
                            int32_t(std::floor((q.y + margin.y) / pattern.py)));
        lo = glm::min(lo, c0);
        hi = glm::max(hi, c1);
    }
    return {lo, hi};
}

Tiling tilesForCells(const Pattern& pattern, const std::vector<glm::ivec2>& cells, glm::dvec2 margin) {
    if (cells.empty()) return {};
    // Range of cells (relative to its own tile) that the pattern's vertices, grown by the
    // margin, fall into.
    const TileReach reach = tileReach(pattern, margin);
    const glm::ivec2 lo = reach.lo, hi = reach.hi;
    // Tile t reaches cells t + [lo, hi]; so cell c needs tiles c - hi .. c - lo.
    glm::ivec2 cmin = cells[0], cmax = cells[0];
    for (const glm::ivec2& c : cells) {
        cmin = glm::min(cmin, c);
        cmax = glm::max(cmax, c);
    }
    const glm::ivec2 minTile = cmin - hi, dims = (cmax - lo) - minTile + 1;
    std::vector<int32_t> marks(size_t(dims.x) * size_t(dims.y), -1);
    for (const glm::ivec2& c : cells)
        for (int32_t y = c.y - hi.y; y <= c.y - lo.y; ++y)
            for (int32_t x = c.x - hi.x; x <= c.x - lo.x; ++x)
                marks[size_t(y - minTile.y) * size_t(dims.x) + size_t(x - minTile.x)] = 0;
    return tilingFromMarks(minTile, dims, std::move(marks));
}

Tiling tilesForRegion(glm::ivec2 first, glm::ivec2 last, bool periodic) {
    if (last.x < first.x || last.y < first.y) return {};
    const glm::ivec2 dims = last - first + 1;
    Tiling t = tilingFromMarks(first, dims, std::vector<int32_t>(size_t(dims.x) * size_t(dims.y), 0));
    t.periodic = periodic;
    return t;
}

}  // namespace knit
