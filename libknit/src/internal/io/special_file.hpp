// special_file.hpp (internal) — inputs that are not regular files (devices, FIFOs, sockets):
// reading one may block forever (a FIFO) or never end (/dev/zero), so every input a file names
// is checked before it is opened.
#pragma once
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include <sys/stat.h>

#include "knit/error.hpp"

namespace knit::impl {

// True when `path` exists and is neither a regular file nor a directory (symlinks followed).
inline bool isSpecialFile(const std::string& path) {
    struct stat st {};
    return stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

// The words every refusal uses.
inline const char* notRegularFile() { return "is not a regular file (a device, FIFO or socket)"; }

// The check before an input file is opened: knit::Error "<path>: cannot open <kind> (does not
// exist)" (or the system's reason), "<path>: is a directory, expected a <expected>", or
// "<path>: is not a regular file (...)". Returns the file's size in bytes.
inline uint64_t requireInputFile(const std::string& path, const std::string& kind, const std::string& expected) {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0)
        throw Error(path + ": cannot open " + kind + " (" +
                    (errno == ENOENT ? std::string("does not exist") : std::string(std::strerror(errno))) + ")");
    if (S_ISDIR(st.st_mode)) throw Error(path + ": is a directory, expected a " + expected);
    if (!S_ISREG(st.st_mode)) throw Error(path + ": " + notRegularFile());
    return uint64_t(st.st_size);
}

}  // namespace knit::impl
