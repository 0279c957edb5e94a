// The memory estimate of a tube export (see export_budget.hpp).
#include "export_budget.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chunks.hpp"

namespace knit::impl {
namespace {

// Draco's encoder per chunk: ~0.5 KB per vertex, plus tables that double with each quantization
// bit at the top of the range. Measured (knit build --export tubes --draco, 2^18-vertex chunks,
// peak resident set minus the scene): ~0.4 KB per vertex at 11-24 bits, then ~120 / 190 /
// 340 MB per chunk at 28 / 29 / 30 bits; 3 x 2^(bits-4) bytes covers those.
double dracoChunkBytes(double vertices, const ExportOptions& o) {
    const int bits = std::max({o.dracoBits, o.dracoNormalBits, o.dracoTexcoordBits});
    return vertices * 512 + 3 * std::ldexp(1.0, bits - 4);
}

}  // namespace

void checkTubeExportBudget(const Polylines& curves, const TubeOptions& tube, const ExportOptions& options, bool gltf) {
    const TubeCounts all = tubeCounts(curves, tube);
    if (all.vertices == 0) return;
    // Step 1: the largest chunk; its triangles in proportion.
    const double chunk =
        std::max(std::min(double(options.chunkVertices), all.vertices), double(all.largestCurveVertices));
    const double triangles = chunk * all.triangles / all.vertices;
    // Step 2: the bytes of one chunk in memory (glTF also holds its encoded buffers), then all in flight.
    double perChunk = tubeMeshBytes(chunk, triangles) * (gltf ? 2 : 1);
    if (options.draco) perChunk += dracoChunkBytes(chunk, options);
    const double inFlight = gltf ? double(chunksInFlight()) : 1.0;
    std::ostringstream what;
    what.precision(3);
    what << chunk << " tube vertices per chunk (" << options.sides << " sides) x " << inFlight
         << (inFlight == 1 ? " chunk" : " chunks") << " in memory at once";
    if (options.draco) what << ", Draco at " << options.dracoBits << " bits";
    options.budget.require(perChunk * inFlight, what.str(),
                           options.draco ? "the Draco position bits, the number of tube sides or the vertices per chunk"
                                         : "the number of tube sides or the vertices per chunk");
}

}  // namespace knit::impl
