// special_file.hpp (internal) — inputs that are not regular files (devices, FIFOs, sockets):
// reading one may block forever (a FIFO) or never end (/dev/zero), so every input a file names
// is checked before it is opened.
#pragma once
#include <string>

#include <sys/stat.h>

namespace knit::detail {

// True when `path` exists and is neither a regular file nor a directory (symlinks followed).
inline bool isSpecialFile(const std::string& path) {
    struct stat st {};
    return stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

// The words every refusal uses.
inline const char* notRegularFile() { return "is not a regular file (a device, FIFO or socket)"; }

}  // namespace knit::detail
