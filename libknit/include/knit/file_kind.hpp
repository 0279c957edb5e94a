// knit/file_kind.hpp — what a file of one of knit's formats is, by its extension, so that a file
// given where another format belongs is named as what it is ("'a.pc2' is a point cache (.pc2), not
// a pattern"), and an output of a fixed format is not written under another format's name.
#pragma once
#include <string>

namespace knit {

// "a mesh (.obj)", "a point cache (.pc2)", "a pattern (.pyp)", ... for the extensions knit reads or
// writes (any case), or "" for any other name.
std::string fileKind(const std::string& path);

}  // namespace knit
