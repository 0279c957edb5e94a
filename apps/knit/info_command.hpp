// info_command.hpp — `knit info`: describe a pattern (period, radius, counts, edges crossing each
// side, loops of a 1x1 tiling), as text or JSON.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace knit::cli {

struct InfoCommand {
    CLI::App* command = nullptr;  // set by addInfoCommand
    std::string pattern;          // file or built-in name
    bool json = false;
};

// Registers the subcommand and its flags on `app`, bound to `info` (which must outlive parsing).
void addInfoCommand(CLI::App& app, InfoCommand& info);

// Prints the description on stdout. Throws knit::Error on bad input.
int runInfo(const InfoCommand& info);

}  // namespace knit::cli
