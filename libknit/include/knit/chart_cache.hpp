// knit/chart_cache.hpp — relaxed chart patterns cached on disk, so `--pattern` with a chart
// relaxes it once.
//
// Cache folder: $KNIT_CACHE_DIR if set, else $XDG_CACHE_HOME/libknit, else ~/.cache/libknit (no
// cache when none can be created). Key: FNV-1a 64 of the chart text and every option
// (chart-<16 hex digits>.pyp). Entries are written to a temporary file and renamed (atomic);
// an unreadable entry is relaxed again and replaced.
#pragma once
#include <string>

#include "knit/chart_pattern.hpp"
#include "knit/pattern.hpp"

namespace knit {

// The cache file name for this chart text and options (no folder).
std::string chartCacheKey(const std::string& chartText, const ChartPatternOptions& options);
// The cache folder ("" when there is none).
std::string chartCacheDir();

// The relaxed pattern of the chart text (parsed with `source` in messages), from the cache or
// relaxed now and stored. Throws knit::Error for a bad chart.
Pattern cachedChartPattern(const std::string& chartText, const std::string& source,
                           const ChartPatternOptions& options = {});

}  // namespace knit
