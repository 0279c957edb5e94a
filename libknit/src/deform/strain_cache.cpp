// Strain tables cached on disk (see knit/strain.hpp, "cached tables"), so a pattern's table is
// made on its first use and read afterwards.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "knit/chart_cache.hpp"
#include "knit/error.hpp"
#include "knit/strain.hpp"
#include "util/hash.hpp"

namespace knit {

std::string strainCacheKey(const Pattern& pattern, const StrainTableOptions& o) {
    std::ostringstream key;
    key.precision(17);
    // The version names the table solver: bump it whenever the relaxation changes what a table holds
    // (v3: cells of 65-200 vertices on the sparse Newton path; v2: stiff yarn, contact barrier,
    // damped Newton), so no cached table of older code is served.
    key << "strain v3";
    for (int n : o.samples) key << ' ' << n;
    for (double v : {o.sxRange[0], o.sxRange[1], o.saRange[0], o.saRange[1], o.syRange[0], o.syRange[1], o.stretch,
                     o.bend, o.contact, o.barrier, o.contactDistance, o.barrierDistance})
        key << ' ' << v;
    key << ' ' << o.maxIterations;
    if (o.startsPerSample != 1) key << " starts " << o.startsPerSample;
    key << '\n';
    Pattern unnamed = pattern;  // the same cell under another file name is the same table
    unnamed.name.clear();
    writePyp(key, unnamed);
    char name[48];
    std::snprintf(name, sizeof name, "strain-%016llx.npy", static_cast<unsigned long long>(util::fnv1a(key.str())));
    return name;
}

namespace {

std::string entryPath(const Pattern& pattern, const StrainTableOptions& options) {
    const std::string dir = chartCacheDir();
    return dir.empty() ? "" : dir + "/" + strainCacheKey(pattern, options);
}

}  // namespace

CachedStrainTable findCachedStrainTable(const Pattern& pattern, const StrainTableOptions& options) {
    CachedStrainTable c;
    c.path = entryPath(pattern, options);
    std::error_code ec;
    if (c.path.empty() || !std::filesystem::exists(c.path, ec)) return c;
    try {
        auto t = std::make_shared<StrainTable>(loadStrainTable(c.path));
        checkStrainTable(*t, pattern);
        c.table = std::move(t);
    } catch (const Error&) {
        // unreadable or not this pattern's: made again and replaced
    }
    return c;
}

CachedStrainTable cachedStrainTable(const Pattern& pattern, const StrainTableOptions& options,
                                    const std::function<StrainTable()>& make) {
    CachedStrainTable c = findCachedStrainTable(pattern, options);
    if (c.table) return c;
    const auto t0 = std::chrono::steady_clock::now();
    auto t = std::make_shared<StrainTable>(make ? make() : makeStrainTable(pattern, options));
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    c.made = true;
    if (!c.path.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(std::filesystem::path(c.path).parent_path(), ec);
        try {
            writeStrainTable(*t, c.path);
            t->source = c.path;
        } catch (const Error&) {
            c.path.clear();  // a read-only or full cache folder: the table is still used
        }
    }
    c.table = std::move(t);
    return c;
}

}  // namespace knit
