// path_collisions.hpp — refuses a command whose outputs overwrite one of its inputs or each other
// (output = input mesh, report = output, report = the glTF's .bin, PNG = EXR), by file identity,
// before any work is done.
#pragma once
#include <string>
#include <vector>

namespace knit::cli {

struct NamedPath {
    std::string role;  // how the message names it: "-o", "--report", "--mesh"
    std::string path;  // empty: not given (skipped)
};

// Two paths are the same file when both exist with the same device and inode, or when their
// canonical forms (symlinks and ".." resolved as far as the path exists) are equal. Throws
// knit::Error naming both flags when an output is an input or another output.
void refuseCollidingPaths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// An output of one fixed format (`kind` as knit/file_kind.hpp names it: "a pattern", with its usual
// extension `ext`) refused under the name of another knit format: `knit chart -o c.obj` wrote a
// pattern under a mesh's name. Other names (no extension, one knit does not use) are written.
void refuseOtherFormatName(const std::string& flag, const std::string& path, const std::string& kind,
                           const std::string& ext);

// The external buffer a .gltf output writes first ("<stem>.bin" next to it); "" for other formats.
std::string gltfBufferOf(const std::string& output);

}  // namespace knit::cli
