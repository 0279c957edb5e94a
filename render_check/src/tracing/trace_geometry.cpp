// The geometry mode factory.
#include "trace_geometry.hpp"

#include "knit/error.hpp"

namespace knit {

uint32_t TraceGeometry::ignoredPrimitive(const TraceHit&) const { return RTC_INVALID_GEOMETRY_ID; }

std::unique_ptr<TraceGeometry> makeTraceGeometry(const PlyGeometry& plies, const TraceSceneOptions& options) {
    switch (options.mode) {
        case GeometryMode::Curves: return makeCurveGeometry(plies);
        case GeometryMode::Tubes: return makeTubeGeometry(plies, options.tubeSides);
        case GeometryMode::Grid: return makeGridGeometry(plies, options.segmentCells);
    }
    throw Error("cannot render: unknown geometry mode");
}

}  // namespace knit
