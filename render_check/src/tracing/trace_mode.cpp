// Names of the tracer's geometry modes.
#include "knit/trace_mode.hpp"

#include "knit/error.hpp"

namespace knit {

const char* modeName(GeometryMode mode) {
    switch (mode) {
        case GeometryMode::Curves: return "curves";
        case GeometryMode::Tubes: return "tubes";
        case GeometryMode::Grid: return "grid";
    }
    return "?";
}

GeometryMode parseMode(const std::string& name) {
    if (name == "curves") return GeometryMode::Curves;
    if (name == "tubes") return GeometryMode::Tubes;
    if (name == "grid") return GeometryMode::Grid;
    throw Error("cannot render: unknown geometry mode '" + name + "' (expected curves, tubes or grid)");
}

}  // namespace knit
