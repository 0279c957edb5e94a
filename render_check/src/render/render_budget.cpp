// The memory estimate of a render (see render_budget.hpp).
#include "render_budget.hpp"

#include <sstream>

#include "knit/sweep.hpp"

namespace knit::impl {
namespace {

// Bytes per element, measured with `knit render --report` (sceneMemoryBytes + the shading data
// over the segments or triangles of a 64000-segment scene; peak resident set of a 1024 x 1024
// render with PNG and EXR minus a 64 x 64 one) and rounded up: curves 73 B per segment, grid
// 29 B per segment, tubes 88 B per triangle (8 sides), image 42 B per pixel.
constexpr double kBytesPerPixel = 64;
constexpr double kBytesPerCurveSegment = 128;
constexpr double kBytesPerGridSegment = 64;
constexpr double kBytesPerTubeTriangle = 128;

std::string counted(double n, const char* what) {
    std::ostringstream s;
    s.precision(3);
    s << n << ' ' << what;
    return s.str();
}

}  // namespace

void checkRenderBudget(const Plies& plies, const RenderOptions& o) {
    // Step 1: the image and its buffers.
    const double pixels = double(o.width) * double(o.height);
    o.budget.require(pixels * kBytesPerPixel, counted(pixels, "pixels of the image"),
                     "the image width or the image height");
    // Step 2: the geometry of the mode.
    const Polylines& c = plies.curves;
    double segments = 0;
    for (size_t k = 0; k < c.curveCount(); ++k)
        if (c.size(k) > 1) segments += double(c.size(k) - 1) + (c.isClosed(k) ? 1 : 0);
    if (o.mode == GeometryMode::Tubes) {
        TubeOptions tube;
        tube.sides = o.tubeSides;
        const double triangles = tubeCounts(c, tube).triangles;
        o.budget.require(triangles * kBytesPerTubeTriangle + segments * kBytesPerGridSegment,
                         counted(triangles, "tube triangles"),
                         "the traced tube sides (or use the geometry mode curves)");
    } else {
        const bool grid = o.mode == GeometryMode::Grid;
        o.budget.require(segments * (grid ? kBytesPerGridSegment : kBytesPerCurveSegment),
                         counted(segments, "ply segments"),
                         "the samples per turn or the repeats, or raise the ply pitch,");
    }
}

}  // namespace knit::impl
