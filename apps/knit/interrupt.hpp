// interrupt.hpp — SIGINT / SIGTERM turned into a flag that long loops check between steps, so
// an interrupted run unwinds (temporary files are removed) instead of dying mid-write.
#pragma once

namespace knit::cli {

// Installs the handlers for its lifetime (restores the previous ones after); a second signal
// while the flag is set gets the default action (terminates at once).
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    // Throws knit::Error "interrupted by signal N" when a signal arrived.
    void check() const;
};

}  // namespace knit::cli
