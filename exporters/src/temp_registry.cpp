// The registry of live temporary files and the signal handler that removes them (see
// temp_registry.hpp). The handler only uses async-signal-safe calls: unlink, sigaction, raise.
#include "temp_registry.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace knit::detail {
namespace {

constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4096;

// One temporary path. state: 0 free, 1 being filled in, 2 live (the handler unlinks it).
struct Slot {
    std::atomic<int> state{0};
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

void removeLiveTempFiles(int sig) {
    Registry& r = registry();
    for (Slot& s : r.slots)
        if (s.state.load() == 2) ::unlink(s.path);
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

int registerTempFile(const std::string& path) {
    Registry& r = registry();
    std::call_once(r.installed, installHandler);
    if (path.size() >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!r.slots[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(r.slots[i].path, path.c_str(), path.size() + 1);
        r.slots[i].state.store(2);
        return i;
    }
    return -1;
}

void unregisterTempFile(int slot) {
    if (slot >= 0 && slot < kSlots) registry().slots[slot].state.store(0);
}

}  // namespace knit::detail
