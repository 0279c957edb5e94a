// `knit generate`: generate the pattern and write it atomically as .pyp.
#include "generate_command.hpp"

#include <cstdio>

#include "knit/export.hpp"
#include "path_collisions.hpp"
#include "knit/pattern.hpp"

namespace knit::cli {

void addGenerateCommand(CLI::App& app, GenerateCommand& g) {
    StockinetteParams& s = g.stockinette;
    g.command = app.add_subcommand("generate", "Write one of the project's parametric patterns as .pyp");
    g.command->add_option("name", g.name, "Generator: stockinette")
        ->check(CLI::IsMember({"stockinette"}))
        ->capture_default_str();
    g.command->add_option("-o,--output", g.output, "Output .pyp file")->required();
    g.command->add_option("--a", s.a, "Loop width (model units)")->capture_default_str();
    g.command->add_option("--h", s.h, "Loop height (model units)")->capture_default_str();
    g.command->add_option("--d", s.d, "Over/under depth (model units)")->capture_default_str();
    g.command->add_option("--row-gap", s.rowGap, "Extra row spacing (model units)")->capture_default_str();
    g.command->add_option("--model-radius", s.modelRadius, "Yarn radius (model units)")->capture_default_str();
    g.command->add_option("--radius", s.radius, "Yarn radius (metres)")->capture_default_str();
    g.command->add_option("--samples", s.samplesPerStitch, "Samples per stitch")->capture_default_str();
    g.command->add_option("--max-memory", g.maxMemory,
                          "Memory budget (8G, 512M, ...; default min(4G, half the physical memory))");
}

int runGenerate(const GenerateCommand& g) {
    refuseOtherFormatName("-o", g.output, "a pattern", ".pyp");
    StockinetteParams params = g.stockinette;
    if (!g.maxMemory.empty()) params.budget = MemoryBudget(parseMemorySize(g.maxMemory));
    const Pattern p = generateStockinette(params);
    writeFileAtomically(
        g.output, [&](std::ostream& out) { writePyp(out, p); }, false);
    std::printf("wrote %s (%zu vertices, period %.9g x %.9g m)\n", g.output.c_str(), p.points.size(), p.px, p.py);
    return 0;
}

}  // namespace knit::cli
