// libFuzzer target: stitch chart parser. Contract as in fuzz_parsers.hpp: any byte string either
// parses into a chart whose every stitch has a valid source column, or raises knit::Error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "knit/chart.hpp"
#include "knit/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > (1 << 16)) return 0;
    try {
        const knit::Chart chart = knit::parseChart(std::string(reinterpret_cast<const char*>(data), size), "fuzz.chart");
        if (chart.width <= 0 || chart.height <= 0 || chart.kind.size() != size_t(chart.width) * size_t(chart.height)) std::abort();
        for (int r = 0; r < chart.height; ++r)
            for (int c = 0; c < chart.width; ++c) {
                const int s = chart.sourceColumn(r, c);
                if (s < 0 || s >= chart.width) std::abort();
            }
    } catch (const knit::Error&) {
    }
    return 0;
}
