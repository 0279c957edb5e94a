// The memory estimate of a tube export (see export_budget.hpp).
#include "export_budget.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chunks.hpp"

namespace knit::impl {
namespace {

// Draco's encoder per chunk: ~0.5 KB per vertex, plus tables of 2^bits entries. Measured on a
// scene of 6084 tube vertices in one chunk (`knit build -q --mesh plane --mesh-res 8 --repeats 2 2
// --export tubes --draco --draco-bits B -o d.glb`, peak resident set by /usr/bin/time): 15 MB at
// 16 bits, 79 at 24, 272 at 26, 529 at 27, 1045 at 28, 2076 at 29 and 4137 MB at 30: 4 x 2^bits
// bytes. (The earlier model, 3 x 2^(bits-4), was ~20x low: 30 bits passed a 4 GiB budget and
// took 4.1 GB for a few thousand vertices, or ended in std::bad_alloc.)
double dracoChunkBytes(double vertices, const ExportOptions& o) {
    const int bits = std::max({o.dracoBits, o.dracoNormalBits, o.dracoTexcoordBits});
    return vertices * 512 + 4 * std::ldexp(1.0, bits);
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

// Bytes per streamed ply point while its chunk is in memory: the generated point (double), the
// resampled centreline behind it, the float copy written and the glTF buffer. Measured as peak
// resident set / ply points written (`knit build -q --mesh plane --mesh-res 2 --repeats 2 2
// --export plies --ply-pitch P -o o.glb`, /usr/bin/time): 69 B at P = 1e-5 (1.2e7 points, 817 MB)
// and at 3e-6 (3.9e7 points, 2.66 GB), where each of the 6 chunks is one long yarn's plies.
constexpr double kBytesPerStreamedPlyPoint = 72;

void checkStreamedPlyBudget(size_t total, size_t largestChunk, const ExportOptions& options) {
    const double inMemory = std::min(double(total), double(largestChunk) * double(chunksInFlight()));
    std::ostringstream what;
    what.precision(3);
    what << inMemory << " ply vertices in the chunks written at once (" << largestChunk
         << " in the largest: one yarn's plies)";
    options.budget.require(inMemory * kBytesPerStreamedPlyPoint, what.str(),
                           "the samples per turn, or raise the ply pitch,");
}

}  // namespace knit::impl
