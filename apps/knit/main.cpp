// knit — command-line front end. Each subcommand (one file each) only composes library stages
// (knit/scene.hpp) with the exporters (knit/export.hpp) and, when built, the render check
// (knit/render.hpp). This file parses, dispatches and maps errors to exit codes:
// 0 success, 1 bad input (knit::Error, with the flag of each setting it names), 3 internal error,
// CLI11's codes for bad flags.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "animate_command.hpp"
#include "build_command.hpp"
#include "chart_command.hpp"
#include "generate_command.hpp"
#include "info_command.hpp"
#include "knit/error.hpp"
#include "scene_flags.hpp"
#include "setting_flags.hpp"
#ifdef KNIT_HAVE_RENDER_CHECK
#include "render_command.hpp"
#endif
#ifdef KNIT_HAVE_FIT
#include "fit_command.hpp"
#endif

namespace {

int runKnit(int argc, char** argv) {
    using namespace knit::cli;
    CLI::App app{"knit: ply-level knitted fabric on a UV-mapped triangle mesh (libknit)"};
    app.require_subcommand(1);
    app.footer(kSceneHelp);

    // Subcommands, in the order --help lists them.
    BuildCommand build;
    InfoCommand info;
    GenerateCommand generate;
    ChartCommand chart;
    AnimateCommand animate;
    addBuildCommand(app, build);
    addAnimateCommand(app, animate);
    addInfoCommand(app, info);
    addGenerateCommand(app, generate);
    addChartCommand(app, chart);
#ifdef KNIT_HAVE_RENDER_CHECK
    RenderCommand render;
    addRenderCommand(app, render);
#endif
#ifdef KNIT_HAVE_FIT
    FitCommand fit;
    addFitCommand(app, fit);
#endif

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        if (*info.command) return runInfo(info);
        if (*generate.command) return runGenerate(generate);
        if (*chart.command) return runChart(chart);
        if (*build.command) return runBuild(build);
        if (*animate.command) return runAnimate(animate);
#ifdef KNIT_HAVE_RENDER_CHECK
        if (*render.command) return runRender(render);
#endif
#ifdef KNIT_HAVE_FIT
        if (*fit.command) return runFit(fit);
#endif
    } catch (const knit::Error& e) {
        // Library messages name settings in words; the CLI adds the flag that sets each.
        std::fprintf(stderr, "knit: error: %s\n", withFlags(e.what()).c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "knit: internal error: %s\n", e.what());
        return 3;
    }
    return 0;
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
