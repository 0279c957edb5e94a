// The registry of live temporary files and the signal handler that removes them (see
// temp_registry.hpp). The handler only uses async-signal-safe calls: unlink, open, the raw
// getdents64 system call, unlinkat, rmdir, close, sigaction, raise.
#include "temp_registry.hpp"

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace knit::impl {
namespace {

constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4096;

// One temporary path. state: 0 free, 1 being filled in, 2 live (the handler unlinks it).
struct Slot {
    std::atomic<int> state{0};
    bool folder = false;  // a staging folder: its files are removed, then the folder
    char path[kPathBytes];
};

// The one process-wide table a signal handler can reach (a handler gets no context pointer).
struct Registry {
    Slot slots[kSlots];
    struct sigaction previous[2];
    std::once_flag installed;
};

Registry& registry() {
    static Registry r;
    return r;
}

constexpr int kSignals[2] = {SIGINT, SIGTERM};

// Unlinks every entry of a flat folder, then the folder. Entries are read with the raw
// getdents64 call (opendir allocates); unlinking while reading may skip entries, so it reads
// again until a pass removes nothing.
void removeFolderInHandler(const char* path) {
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    alignas(8) char buf[4096];
    for (int pass = 0; pass < 16; ++pass) {
        bool removed = false;
        ::lseek(fd, 0, SEEK_SET);
        for (long n; (n = ::syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0;)
            for (long off = 0; off < n;) {
                unsigned short reclen = 0;  // struct linux_dirent64: ino 8, off 8, reclen 2, type 1, name
                std::memcpy(&reclen, buf + off + 16, sizeof reclen);
                const char* name = buf + off + 19;
                if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0)
                    removed = ::unlinkat(fd, name, 0) == 0 || removed;
                off += reclen;
            }
        if (!removed) break;
    }
    ::close(fd);
    ::rmdir(path);
}

void removeLiveTempFiles(int sig) {
    Registry& r = registry();
    for (Slot& s : r.slots)
        if (s.state.load() == 2) s.folder ? removeFolderInHandler(s.path) : (void)::unlink(s.path);
    // Re-raise with the disposition the process had before (default: terminate by this signal).
    for (int k = 0; k < 2; ++k)
        if (kSignals[k] == sig) ::sigaction(sig, &r.previous[k], nullptr);
    ::raise(sig);
}

void installHandler() {
    Registry& r = registry();
    struct sigaction sa {};
    sa.sa_handler = removeLiveTempFiles;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;
    for (int k = 0; k < 2; ++k) ::sigaction(kSignals[k], &sa, &r.previous[k]);
}

}  // namespace

namespace {

int registerPath(const std::string& path, bool folder) {
    Registry& r = registry();
    std::call_once(r.installed, installHandler);
    if (path.size() >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!r.slots[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(r.slots[i].path, path.c_str(), path.size() + 1);
        r.slots[i].folder = folder;
        r.slots[i].state.store(2);
        return i;
    }
    return -1;
}

}  // namespace

int registerTempFile(const std::string& path) { return registerPath(path, false); }

int registerTempFolder(const std::string& path) { return registerPath(path, true); }

void unregisterTempFile(int slot) {
    if (slot >= 0 && slot < kSlots) registry().slots[slot].state.store(0);
}

}  // namespace knit::impl
