// libFuzzer target: the JSON request bodies of `knit serve`'s API (apps/serve/src/api_request.cpp)
// and the page's chart text: any byte string is either accepted as a request of each endpoint or
// refused with a RequestError whose status is 400 or 413 (chart errors: ChartTextError with a
// line and column of at least 1), never a crash, a hang or another exception.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "api_request.hpp"
#include "chart_job.hpp"

namespace {

template <class Parse>
void refusedOnlyAsBadRequest(Parse parse) {
    try {
        parse();
    } catch (const knit::serve::RequestError& e) {
        if (e.status() != 400 && e.status() != 413) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace knit::serve;
    const std::string body(reinterpret_cast<const char*>(data), size);
    RequestLimits limits;
    limits.maxChartStitches = 64;
    refusedOnlyAsBadRequest([&] {
        const SwatchRequest r = parseSwatchRequest(body, limits);
        try {
            parsePageChart(r.chart, limits.maxChartStitches);
        } catch (const ChartTextError& e) {
            if (e.line() < 1 || e.column() < 1) std::abort();
        }
    });
    refusedOnlyAsBadRequest([&] { parseGarmentRequest(body, limits, false); });
    refusedOnlyAsBadRequest([&] { parseGarmentRequest(body, limits, true); });
    refusedOnlyAsBadRequest([&] { parseCancelRequest(body); });
    return 0;
}
