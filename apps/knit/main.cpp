// knit — command-line front end. Each subcommand (one file each) only composes library stages
// (knit/scene.hpp) with the exporters (knit/export.hpp) and, when built, the render check
// (knit/render.hpp). This file parses, dispatches and maps errors to exit codes:
// 0 success, 1 bad input (knit::Error, with the flag of each setting it names), 3 internal error,
// CLI11's codes for bad flags.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "knit/error.hpp"
#include "scene_flags.hpp"
#include "setting_flags.hpp"

namespace {

int runKnit(int argc, char** argv) {
    using namespace knit::cli;
    CLI::App app{"knit: ply-level knitted fabric on a UV-mapped triangle mesh (libknit)"};
    app.require_subcommand(1);

    // Subcommands, in the order --help lists them. Those that take a scene set the scene footer
    // themselves; it is set here after them, so the others do not inherit it.
    Commands commands;
    addCommands(app, commands);
    app.footer(kSceneHelp);
    if (const std::string unknown = unknownCommand(app, argc, argv); !unknown.empty()) {
        std::fprintf(stderr, "knit: error: %s\n", unknown.c_str());
        return static_cast<int>(CLI::ExitCodes::ExtrasError);
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        return runCommand(commands);
    } catch (const knit::Error& e) {
        // Library messages name settings in words; the CLI adds the flag that sets each.
        std::fprintf(stderr, "knit: error: %s\n", withFlags(e.what()).c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "knit: internal error: %s\n", e.what());
        return 3;
    }
}

}  // namespace

int main(int argc, char** argv) {
    // Errors raised while the flags are set up (outside runKnit's own handlers) still exit cleanly.
    try {
        return runKnit(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "knit: internal error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "knit: internal error: unknown exception\n");
    }
    return 3;
}
