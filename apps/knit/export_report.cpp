// The export statistics as the JSON of `knit build --report` (see export_report.hpp).
#include "export_report.hpp"

namespace knit::cli {

nlohmann::json exportReport(const ExportStats& s) {
    nlohmann::json j = {{"format", s.format},
                        {"curves", s.curves},
                        {"vertices", s.vertices},
                        {"triangles", s.triangles},
                        {"chunks", s.chunks},
                        {"maxChunkVertices", s.maxChunkVertices},
                        {"buffers", s.buffers},
                        {"bytes", s.bytes},
                        {"peakMemoryBytes", s.peakMemoryBytes},
                        {"peakMemoryMiB", double(s.peakMemoryBytes) / (1024.0 * 1024.0)},
                        {"seconds", s.seconds}};
    if (s.uncompressedMeshBytes > 0) {
        j["uncompressedMeshBytes"] = s.uncompressedMeshBytes;
        j["compressedMeshBytes"] = s.compressedMeshBytes;
        if (s.compressedMeshBytes > 0)
            j["compressionRatio"] = double(s.uncompressedMeshBytes) / double(s.compressedMeshBytes);
    }
    if (s.surfaceTriangles > 0)
        j["surface"] = {
            {"vertices", s.surfaceVertices}, {"triangles", s.surfaceTriangles}, {"imageBytes", s.imageBytes}};
    return j;
}

}  // namespace knit::cli
