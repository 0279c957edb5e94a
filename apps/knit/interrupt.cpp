// interrupt.cpp — the signal flag of InterruptGuard.
#include "interrupt.hpp"

#include <csignal>
#include <string>

#include "knit/error.hpp"

namespace knit::cli {
namespace {

volatile std::sig_atomic_t gSignal = 0;
void (*gPreviousInt)(int) = SIG_DFL;
void (*gPreviousTerm)(int) = SIG_DFL;

extern "C" void onSignal(int sig) {
    gSignal = sig;
    std::signal(sig, SIG_DFL);  // a second signal terminates at once
}

}  // namespace

InterruptGuard::InterruptGuard() {
    gSignal = 0;
    gPreviousInt = std::signal(SIGINT, onSignal);
    gPreviousTerm = std::signal(SIGTERM, onSignal);
}

InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, gPreviousInt);
    std::signal(SIGTERM, gPreviousTerm);
}

void InterruptGuard::check() const {
    if (gSignal != 0) throw Error("interrupted by signal " + std::to_string(gSignal) + "; no partial output was kept");
}

}  // namespace knit::cli
