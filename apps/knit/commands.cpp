// Every subcommand registered and dispatched (commands.hpp).
#include "commands.hpp"

#include <string>

namespace knit::cli {

void addCommands(CLI::App& app, Commands& c) {
    addBuildCommand(app, c.build);
    addAnimateCommand(app, c.animate);
    addBindCommand(app, c.bind);
    addCacheCommand(app, c.cache);
    addInfoCommand(app, c.info);
    addGenerateCommand(app, c.generate);
    addChartCommand(app, c.chart);
    addStrainTableCommand(app, c.strainTable);
    addServeCommand(app, c.serve);
#ifdef KNIT_HAVE_RENDER_CHECK
    addRenderCommand(app, c.render);
#endif
#ifdef KNIT_HAVE_FIT
    addFitCommand(app, c.fit);
#endif
}

std::string unknownCommand(const CLI::App& app, int argc, const char* const* argv) {
    // Walk the words down the command tree (knit, knit cache, ...) while each level has
    // subcommands; the first word that names none of them is the unknown one.
    const CLI::App* level = &app;
    std::string path = "knit";
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.empty() || word[0] == '-') return {};
        const auto subs = level->get_subcommands([](const CLI::App*) { return true; });
        if (subs.empty()) return {};
        const CLI::App* found = nullptr;
        std::string names;
        for (const CLI::App* sub : subs) {
            if (sub->check_name(word)) found = sub;
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (found == nullptr) {
            const std::string shown = word.size() > 40 ? word.substr(0, 40) + "..." : word;
            return "'" + shown + "' is not a " + path + " command; the commands are " + names + " (" + path +
                   " --help describes them)";
        }
        level = found;
        path += " " + found->get_name();
    }
    return {};
}

int runCommand(const Commands& c) {
    if (*c.info.command) return runInfo(c.info);
    if (*c.generate.command) return runGenerate(c.generate);
    if (*c.chart.command) return runChart(c.chart);
    if (*c.strainTable.command) return runStrainTable(c.strainTable);
    if (*c.build.command) return runBuild(c.build);
    if (*c.animate.command) return runAnimate(c.animate);
    if (*c.serve.command) return runServe(c.serve);
    if (*c.bind.command) return runBind(c.bind);
    if (*c.cache.command) return runCache(c.cache);
#ifdef KNIT_HAVE_RENDER_CHECK
    if (*c.render.command) return runRender(c.render);
#endif
#ifdef KNIT_HAVE_FIT
    if (*c.fit.command) return runFit(c.fit);
#endif
    return 0;
}

}  // namespace knit::cli
