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

// The external buffer a .gltf output writes first ("<stem>.bin" next to it); "" for other formats.
std::string gltfBufferOf(const std::string& output);

}  // namespace knit::cli
