// libFuzzer target: strain table reader, axes text + .npy (see fuzz_parsers.hpp for the contract).
#include "fuzz_parsers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    knit::fuzz::runStrainTable(data, size);
    return 0;
}
