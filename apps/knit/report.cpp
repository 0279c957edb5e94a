// JSON reports and scene notes of the commands (see report.hpp).
#include "report.hpp"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "knit/export.hpp"

namespace knit::cli {

void writeReport(const std::string& path, const nlohmann::json& report) {
    writeFileAtomically(path, [&](std::ostream& out) { out << report.dump(2) << '\n'; }, false);
}

void printWarnings(const Scene& s) {
    if (s.grid.overlappingCharts.empty()) return;
    std::string pairs;
    const size_t shown = std::min<size_t>(s.grid.overlappingCharts.size(), 8);
    for (size_t k = 0; k < shown; ++k)
        pairs += (pairs.empty() ? "" : ", ") + std::to_string(s.grid.overlappingCharts[k].x) + "/" +
                 std::to_string(s.grid.overlappingCharts[k].y);
    if (shown < s.grid.overlappingCharts.size())
        pairs += " and " + std::to_string(s.grid.overlappingCharts.size() - shown) + " more pairs";
    std::fprintf(stderr, "knit: note: %s: UV charts overlap (%s); each chart is tiled and knitted on its own\n",
                 s.mesh.name.c_str(), pairs.c_str());
}

}  // namespace knit::cli
