// stale_temporaries.hpp (internal) — temporaries left by killed runs. A run killed by SIGKILL, a
// power loss or the out-of-memory killer cannot remove its temporary files (`.<name>.<pid>.<n>.tmp`,
// atomic_file.hpp) or staging folders (`.knit-staging.<pid>.<n>.tmp`, output_transaction.hpp).
// Every writer holds an advisory lock (flock) on its temporary while it exists; the kernel drops
// it when the process dies, however it dies. A later writer sweeps the folder it writes to once:
// it removes a temporary only when its name is one of ours, it belongs to this user, the process
// its name carries is gone (kill(pid, 0) says ESRCH) and nobody holds its lock (a process of
// another machine or PID namespace sharing the folder holds it).
#pragma once
#include <cstddef>
#include <optional>
#include <string>

namespace knit::impl {

// What a directory entry's name says, if it is one of our temporaries.
struct TemporaryName {
    bool stagingFolder = false;  // .knit-staging.<pid>.<n>.tmp; else .<name>.<pid>.<n>.tmp
    long pid = 0;
};
std::optional<TemporaryName> parseTemporaryName(const std::string& name);

// Takes the lock that marks `path` (a temporary file or staging folder) as in use; returns the
// descriptor holding it, or -1 when it cannot (the temporary is then only protected by its pid).
int lockTemporary(const std::string& path);
void unlockTemporary(int fd);  // -1 is ignored

// Removes the stale temporaries (see above) in `folder` ("" = the working folder); returns how
// many it removed. Never throws; anything it cannot read or remove is left as it is.
size_t removeStaleTemporaries(const std::string& folder);
// The same, at most once per folder in this process (writers call it before writing there).
void removeStaleTemporariesOnce(const std::string& folder);

}  // namespace knit::impl
