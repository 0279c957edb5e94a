// export_helpers.hpp — the export calls the glTF tests share: curves in, options, stats out.
#pragma once
#include <string>
#include <vector>

#include "knit/export.hpp"

namespace knit::test {

// Exports `c` (constant radius, optional yarn of each curve) with `o`.
inline ExportStats exportWith(const Polylines& c, double radius, ExportOptions o,
                              const std::vector<uint32_t>* yarns = nullptr,
                              const std::string& materialExtrasJson = "") {
    ExportInput in;
    in.curves = &c;
    in.radius = radius;
    in.yarnOfCurve = yarns;
    in.materialExtrasJson = materialExtrasJson;
    return exportCurves(in, o);
}

// Options for a tube export to `path` with `sides` ring vertices.
inline ExportOptions tubeOptions(const std::string& path, int sides = 8) {
    ExportOptions o;
    o.path = path;
    o.what = ExportWhat::Tubes;
    o.sides = sides;
    return o;
}

}  // namespace knit::test
