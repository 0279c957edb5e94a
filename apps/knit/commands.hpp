// commands.hpp — every subcommand of `knit`, registered on one CLI::App in the order --help lists
// them, and the dispatch to the one that was given. main.cpp and the flag tests (tests/cli) use
// the same registration, so a test sees exactly the options a user can type.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "animate_command.hpp"
#include "bind_command.hpp"
#include "build_command.hpp"
#include "cache_command.hpp"
#include "chart_command.hpp"
#include "generate_command.hpp"
#include "info_command.hpp"
#include "strain_table_command.hpp"
#include "serve_command.hpp"
#ifdef KNIT_HAVE_RENDER_CHECK
#include "render_command.hpp"
#endif
#ifdef KNIT_HAVE_FIT
#include "fit_command.hpp"
#endif

namespace knit::cli {

struct Commands {
    BuildCommand build;
    InfoCommand info;
    GenerateCommand generate;
    ChartCommand chart;
    AnimateCommand animate;
    StrainTableCommand strainTable;
    ServeCommand serve;
    BindCommand bind;    // issue 26: bound scene files
    CacheCommand cache;  // issue 26: chunk merge
#ifdef KNIT_HAVE_RENDER_CHECK
    RenderCommand render;
#endif
#ifdef KNIT_HAVE_FIT
    FitCommand fit;
#endif
};

// Adds every subcommand to `app`; `commands` receives their parsed values.
void addCommands(CLI::App& app, Commands& commands);

// The refusal of a command line with a word where a subcommand belongs (`knit views`,
// `knit cache frobnicate`), naming the word and listing that level's subcommands; empty when every
// such word is a subcommand or a flag comes first.
std::string unknownCommand(const CLI::App& app, int argc, const char* const* argv);

// Runs the subcommand that was parsed (its exit code); 0 when none was.
int runCommand(const Commands& commands);

}  // namespace knit::cli
