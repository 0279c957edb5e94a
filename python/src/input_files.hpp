// python/src/input_files.hpp — refuses writing over a file the call reads: export_scene,
// save_bound_scene and strain_table(path=...) onto the scene's pattern or mesh file (the command
// line refuses the same with its flags, apps/knit/path_collisions.hpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace knitpy {

// Throws knit::Error when `path` (the keyword `keyword`) is the same file as one of `inputs`
// ({what, path}: "the scene's pattern", "p.pyp"); inputs that are not existing files (a built-in
// name) are skipped.
void refuseWritingOverInputs(const std::string& keyword, const std::string& path,
                             const std::vector<std::pair<std::string, std::string>>& inputs);

}  // namespace knitpy
