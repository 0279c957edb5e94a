// generate_command.hpp — `knit generate`: write one of the project's parametric patterns as .pyp.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "knit/generator.hpp"

namespace knit::cli {

struct GenerateCommand {
    CLI::App* command = nullptr;  // set by addGenerateCommand
    std::string name = "stockinette";
    std::string output;  // .pyp path (required)
    StockinetteParams stockinette;
    std::string maxMemory;  // empty: MemoryBudget's default
};

// Registers the subcommand and its flags on `app`, bound to `generate` (which must outlive parsing).
void addGenerateCommand(CLI::App& app, GenerateCommand& generate);

// Generates and writes the pattern; prints one line on stdout. Throws knit::Error on bad input.
int runGenerate(const GenerateCommand& generate);

}  // namespace knit::cli
