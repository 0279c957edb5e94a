// python/src/memory_budget_arg.hpp — the max_memory keyword argument -> knit::MemoryBudget.
#pragma once
#include <string>

#include "knit/budget.hpp"
#include "knit/error.hpp"

namespace knitpy {

// "" = the default budget (min(4 GiB, half the physical memory)), else a size such as "8G"; a
// text that is not a size raises knit.Error ("the memory budget (max_memory) 'lots': expected a
// size ...": the library's words, the keyword added by the module's translator).
inline knit::MemoryBudget memoryBudgetArg(const std::string& maxMemory) {
    if (maxMemory.empty()) return knit::MemoryBudget();
    return knit::MemoryBudget(knit::parseMemorySize(maxMemory));
}

}  // namespace knitpy
