// Small timing helpers shared by the benchmarks that report process CPU time themselves (the
// machine may be shared, so CPU seconds compare runs better than wall time).
#pragma once

#include <time.h>

#include <algorithm>
#include <vector>

namespace knit::bench {

// CPU seconds used so far by this process, all threads together.
inline double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The median of the samples (the upper one of the middle two for an even count).
inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace knit::bench
