// formats.hpp (internal) — one writer per file format, called by exportCurves().
#pragma once
#include <string>

#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit::impl {

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
