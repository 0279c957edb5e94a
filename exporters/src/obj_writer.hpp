// obj_writer.hpp (internal) — OBJ tube meshes (writeObjPolylines is public in knit/export.hpp).
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit::detail {

void writeObjTubeHeader(std::ostream& out, const std::string& header);
// One chunk of a streamed tube mesh; `vertexBase` = vertices written by earlier chunks.
void writeObjTubeChunk(std::ostream& out, const TubeMesh& mesh, uint64_t vertexBase);

}  // namespace knit::detail
