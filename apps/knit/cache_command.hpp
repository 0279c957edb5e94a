// cache_command.hpp — `knit cache merge`: PC2 chunks baked on a farm (`knit animate --first A
// --last B`) joined into one cache, checked to tile one frame range exactly once.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace knit::cli {

struct CacheCommand {
    CLI::App* command = nullptr;  // `cache`, set by addCacheCommand
    CLI::App* merge = nullptr;    // `cache merge`
    std::vector<std::string> chunks;
    std::string output;
};

void addCacheCommand(CLI::App& app, CacheCommand& cache);

// Merges; prints a summary on stdout. Throws knit::Error.
int runCache(const CacheCommand& cache);

}  // namespace knit::cli
