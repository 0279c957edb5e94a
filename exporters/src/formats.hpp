// formats.hpp (internal) — the formats the exporters write (the one list of their extensions:
// what each holds and how it stores coordinates) and one writer per scene format, called by
// exportCurves().
#pragma once
#include <string>

#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit::impl {

struct FormatJob;

// One row per written format. Every check of an output's extension reads this table.
struct Format {
    const char* extension;                // lower case, without the dot
    bool pointCache;                      // a point cache (PointCacheWriter), not a scene export (exportScene)
    bool tubes;                           // holds tube meshes, not only curves
    bool gltf;                            // glTF JSON or binary
    bool float32;                         // coordinates stored as float32 (glTF: relative to each chunk's origin)
    void (*write)(const FormatJob& job);  // the scene writer (null for point caches)
};

// The format of `path` by its extension (case-insensitive); null when no exporter writes it.
const Format* formatOf(const std::string& path);
// The scene formats (optionally only those holding tubes) as ".obj, .ply, ..." in table order,
// joined by `separator`.
std::string sceneFormatList(const char* separator, bool tubesOnly = false);

// Everything a format writer needs: validated input and options, and the stats to fill
// (format, curves, vertices, triangles, chunks, bytes, ...; seconds and peak memory are set by
// the caller).
struct FormatJob {
    const ExportInput& input;
    const ExportOptions& options;
    TubeOptions tube;    // sides, caps, seed normals
    bool tubes = false;  // what == Tubes
    std::string header;  // one-line description for file comments
    ExportStats& stats;
};

void exportObj(const FormatJob& job);
void exportPly(const FormatJob& job);
void exportBcc(const FormatJob& job);
void exportPbrt(const FormatJob& job);
void exportGltf(const FormatJob& job, bool binary);

}  // namespace knit::impl
