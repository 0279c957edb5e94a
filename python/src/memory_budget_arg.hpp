// python/src/memory_budget_arg.hpp — the max_memory keyword argument -> knit::MemoryBudget.
#pragma once
#include <string>

#include "knit/budget.hpp"
#include "knit/error.hpp"

namespace knitpy {

// "" = the default budget (min(4 GiB, half the physical memory)), else a size such as "8G";
// a text that is not a size raises knit.Error naming the keyword (not the CLI's flag).
inline knit::MemoryBudget memoryBudgetArg(const std::string& maxMemory) {
    if (maxMemory.empty()) return knit::MemoryBudget();
    try {
        return knit::MemoryBudget(knit::parseMemorySize(maxMemory));
    } catch (const knit::Error&) {
        throw knit::Error("max_memory '" + maxMemory +
                          "': expected a size such as '8G', '512M', '64K' or a number "
                          "of bytes");
    }
}

}  // namespace knitpy
