// bound_scene_file.hpp (internal) — a bound scene file's bytes in memory for readBoundScene
// (knit/bound_scene.hpp): mapped read-only (POSIX mmap), or read into memory where mapping is
// not possible, with an owner that keeps them valid for the views a loaded scene holds.
#pragma once
#include <memory>
#include <string>
#include <string_view>

#include "knit/budget.hpp"

namespace knit::impl {

enum class BoundSceneAccess {
    Map,   // mmap, and read into memory when mapping fails
    Read,  // read into memory (what a failed map falls back to)
};

struct BoundSceneFile {
    std::shared_ptr<const void> owner;  // unmaps / frees the bytes when the last view is gone
    std::string_view bytes;
    bool mapped = false;
};

// The bytes of the file at `path` (its size checked against `budget` first). Throws knit::Error
// naming the file when it cannot be opened, mapped nor read.
BoundSceneFile openBoundSceneFile(const std::string& path, const MemoryBudget& budget,
                                  BoundSceneAccess access = BoundSceneAccess::Map);

}  // namespace knit::impl
