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
    if (argc < 2 || argv[1][0] == '-') return {};
    const std::string word = argv[1];
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->check_name(word)) return {};
        names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    const std::string shown = word.size() > 40 ? word.substr(0, 40) + "..." : word;
    return "'" + shown + "' is not a knit command; the commands are " + names + " (knit --help describes them)";
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
