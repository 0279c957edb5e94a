// knit/budget.hpp — how much memory one command may use, and the checks that refuse a step
// whose estimated size (from its counts, before allocating) would exceed it.
#pragma once
#include <cstdint>
#include <string>

namespace knit {

class MemoryBudget {
public:
    // The default budget: min(4 GiB, half the physical memory).
    MemoryBudget();
    explicit MemoryBudget(uint64_t bytes) : bytes_(bytes) {}

    uint64_t bytes() const { return bytes_; }

    // Throws knit::Error when `estimateBytes` (may be huge or inf) is over the budget:
    // "needs about X GiB (estimate) for <what>, over the memory budget of Y GiB; lower
    // <option> or raise the memory budget". `what` names the counts ("1e10 pattern cells"),
    // `option` the settings that drive them in words ("the repeats"; knit/setting_spelling.hpp).
    void require(double estimateBytes, const std::string& what, const std::string& option) const;

    static uint64_t defaultBytes();

private:
    uint64_t bytes_;
};

// "8G", "512M", "1.5g", "64K", "2T" or plain bytes; throws knit::Error naming the memory budget
// for anything else (or zero).
uint64_t parseMemorySize(const std::string& text);

// Bytes as GiB for messages ("3.2 GiB", "0.0012 GiB").
std::string formatGiB(double bytes);

}  // namespace knit
