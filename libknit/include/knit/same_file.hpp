// same_file.hpp — whether two paths name one file, for the front ends' "an output would replace
// an input" refusals (the command line's flags, the Python module's keywords).
#pragma once
#include <string>

namespace knit {

// Two paths are the same file when both exist with the same device and inode (hard links and
// symlinks count), or when neither exists and their canonical forms (symlinks and ".." resolved
// as far as the path exists) are equal.
bool sameFile(const std::string& a, const std::string& b);

}  // namespace knit
