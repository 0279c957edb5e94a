// mesh_upload.hpp — a garment mesh uploaded from the page (POST /api/mesh): OBJ, or glTF 2.0
// (.glb / .gltf) with every buffer and image inside the file.
#pragma once
#include <string>

#include "knit/base_mesh.hpp"
#include "knit/budget.hpp"
#include "temp_folder.hpp"

namespace knit::serve {

// `name` is the user's file name, used only for its extension and in messages. An OBJ is written
// to a server-named file in `temp` for the reader and removed after. Throws RequestError 415 for
// another extension, knit::Error (naming `name`) for what the readers refuse, including a glTF
// that refers to files outside itself.
BaseMesh loadUploadedMesh(const std::string& bytes, const std::string& name, TempFolder& temp,
                          const MemoryBudget& budget);

}  // namespace knit::serve
