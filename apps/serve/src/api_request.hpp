// api_request.hpp — the JSON bodies of `knit serve`'s API (docs/serve.md), parsed and checked
// before any work starts. Every refusal is a RequestError naming the field in the page's words
// ("\"repeats\" must be two numbers from 1 to 64") with the HTTP status to answer.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "knit/tiling.hpp"
#include "knit/view.hpp"

namespace knit::serve {

class RequestError : public std::runtime_error {
public:
    RequestError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
    int status() const { return status_; }

private:
    int status_;
};

// Limits on what one request may ask for (checked before any work).
struct RequestLimits {
    size_t maxChartBytes = 64 * 1024;  // chart text
    int maxChartStitches = 1024;       // width x height of the chart grid
    double maxRepeats = 64;            // swatch repeats per direction
    int maxImageSide = 4096;           // view width / height in pixels
};

// What every job names: the page it comes from (a newer job of the same session cancels the older).
struct JobRequest {
    std::string session;  // 1..64 characters of [A-Za-z0-9_-]
    std::string chart;    // chart text (knit/chart.hpp)
};

// The swatch (POST /api/swatch): the chart relaxed and tiled on a small plane.
struct SwatchRequest : JobRequest {
    std::array<double, 2> repeats{0, 0};  // 0 0: as many as make about 12 stitches each way
};

enum class DownloadFormat { Pyp, Glb, Pc2 };

// The garment (POST /api/garment) and downloads (POST /api/download): the chart on a mesh.
struct GarmentRequest : JobRequest {
    std::string mesh = "drape";                   // a built-in mesh name or an upload id ("upload-3")
    std::optional<Gauge> gauge;                   // or repeats
    std::array<double, 2> repeats{0, 0};          // 0 0 with no gauge: the default gauge
    std::optional<View> view;                     // the page's camera (level of detail); none: the default framing
    DownloadFormat format = DownloadFormat::Glb;  // downloads only
};

// Parse the body; throw RequestError (400 for malformed JSON or a missing/ill-typed field, 413 for
// a chart over the size limit).
SwatchRequest parseSwatchRequest(const std::string& body, const RequestLimits& limits);
GarmentRequest parseGarmentRequest(const std::string& body, const RequestLimits& limits, bool download);
// POST /api/cancel: the session id alone.
std::string parseCancelRequest(const std::string& body);

}  // namespace knit::serve
