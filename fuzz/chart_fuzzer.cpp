// libFuzzer target: stitch chart parser and initial cell (fuzz_parsers.hpp, runChart): any byte
// string either parses into a chart whose every stitch has a valid source column, or raises
// knit::Error.
#include "fuzz_parsers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    knit::fuzz::runChart(data, size);
    return 0;
}
