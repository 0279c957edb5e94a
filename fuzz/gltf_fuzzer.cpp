// libFuzzer target: glTF / GLB base-mesh reader (see fuzz_parsers.hpp for the contract).
#include "fuzz_parsers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    knit::fuzz::runGltf(data, size);
    return 0;
}
