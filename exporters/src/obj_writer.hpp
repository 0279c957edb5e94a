// obj_writer.hpp (internal) — OBJ polylines and tube meshes.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit::impl {

// OBJ polylines: one `l` record per curve; a closed curve repeats its first index at the end.
void writeObjPolylines(std::ostream& out, const Polylines& curves, const std::string& header);
void writeObjTubeHeader(std::ostream& out, const std::string& header);
// One chunk of a streamed tube mesh; `vertexBase` = vertices written by earlier chunks.
void writeObjTubeChunk(std::ostream& out, const TubeMesh& mesh, uint64_t vertexBase);

}  // namespace knit::impl
