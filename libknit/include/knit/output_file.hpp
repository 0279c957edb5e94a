// knit/output_file.hpp — output files that appear whole or not at all: every writer of the
// project (the exporters, the renderer's images, the chart cache, the CLI's reports) writes
// through a temporary sibling file renamed when complete, and checks the folder first.
#pragma once
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace knit {

// Writes `path` through a temporary sibling file renamed on success; `write` fills the stream.
// Throws knit::Error naming the path if it cannot be created or written. SIGINT / SIGTERM
// while it is written remove the temporary file.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary);

// Throws knit::Error unless the folder of `path` (".": no folder part) exists, is a folder and
// is writable: "cannot write <what> '<path>': folder '<folder>' does not exist" (or "'<folder>' is
// not a folder", "folder '<folder>' is not writable"); with an empty `what`, "cannot write '<path>': ...".
// Every writer checks its output with it; callers use it to fail before long work.
void requireWritableFolder(const std::string& path, const std::string& what = "");

// Removes what killed runs left in `folder` ("" = the working folder): hidden `.<name>.<pid>.<n>.tmp`
// files and `.knit-staging.<pid>.<n>.tmp` folders of this user whose process is gone and whose
// lock nobody holds (a live writer's, or one of another machine sharing the folder, stay). Every
// writer of the library does this once per folder before writing there; a front end with a writer
// of its own (the Blender add-on's PC2 bake) calls it. Returns how many it removed; never throws.
size_t removeStaleTemporaries(const std::string& folder);

}  // namespace knit
