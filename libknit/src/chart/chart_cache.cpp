// Relaxed chart patterns cached on disk (see knit/chart_cache.hpp).
#include "knit/chart_cache.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "knit/error.hpp"
#include "knit/output_file.hpp"
#include "util/hash.hpp"

namespace knit {
std::string chartCacheKey(const std::string& chartText, const ChartPatternOptions& o) {
    std::ostringstream key;
    key.precision(17);
    // v13: cells of 1000 to 1500 vertices relax preconditioned (long intarsia carries; no built-in
    // changes); v12: intarsia boundaries jumping three or more columns between blocks of rows are carried
    // yarns, not new bobbins (such charts build other cells; no built-in changes); v11: intarsia turns carried two stitches on hold their crossover anchored (charts whose
    // boundaries move two columns relax differently; no built-in changes); v10: cables built at samples per stitch not divisible by 4 changed (chart_topology.cpp,
    // loopParameter); v9: two-column intarsia jumps, one-stitch rows' tails higher. Options at
    // their defaults add nothing to the key.
    key << "v13 " << o.radius << ' ' << o.samplesPerStitch << ' ' << o.restLength << ' ' << o.maxIterations
        << (o.affinePeriod ? " affine" : "") << (o.hessianPreconditioner ? "" : " plain");
    if (o.contact != RelaxOptions{}.contact) key << " contact " << o.contact;
    if (o.relativeEnergyTolerance != RelaxOptions{}.relativeEnergyTolerance ||
        o.energyWindow != RelaxOptions{}.energyWindow)
        key << " energy-stop " << o.relativeEnergyTolerance << ' ' << o.energyWindow;
    key << '\n' << chartText;
    char name[40];
    std::snprintf(name, sizeof name, "chart-%016llx.pyp", static_cast<unsigned long long>(util::fnv1a(key.str())));
    return name;
}

std::string chartCacheDir() {
    if (const char* d = std::getenv("KNIT_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/libknit";
    if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/libknit";
    return "";
}

Pattern cachedChartPattern(const std::string& chartText, const std::string& source,
                           const ChartPatternOptions& options) {
    const Chart chart = parseChart(chartText, source);  // errors name the chart, cached or not
    const std::string dir = chartCacheDir();
    const std::string path = dir.empty() ? "" : dir + "/" + chartCacheKey(chartText, options);
    // Step 1: a cached entry.
    if (!path.empty() && std::filesystem::exists(path)) {
        try {
            Pattern p = loadPyp(path);
            p.name = source;
            return p;
        } catch (const Error&) {
            // unreadable: relax again below and replace it
        }
    }
    // Step 2: relax and store atomically (a failure to store is not an error).
    Pattern p = relaxChart(chart, options).relaxed.pattern;
    p.name = source;
    if (!path.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        try {
            writeFileAtomically(
                path, [&](std::ostream& out) { writePyp(out, p); }, true);
        } catch (const Error&) {
            // a read-only or full cache folder: the pattern is still returned
        }
    }
    return p;
}

}  // namespace knit
