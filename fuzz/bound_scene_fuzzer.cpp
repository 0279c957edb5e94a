// libFuzzer target: bound scene file reader (fuzz_parsers.hpp, runBoundScene): any byte string
// either loads into a scene an Animator evaluates, or raises knit::Error.
#include "fuzz_parsers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    knit::fuzz::runBoundScene(data, size);
    return 0;
}
