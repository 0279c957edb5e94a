// `knit strain-table`: make a pattern's strain table (see strain_table_command.hpp).
#include "strain_table_command.hpp"

#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "interrupt.hpp"
#include "path_collisions.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/output_file.hpp"

namespace knit::cli {

void addStrainTableCommand(CLI::App& app, StrainTableCommand& c) {
    c.command = app.add_subcommand(
        "strain-table",
        "Make a pattern's strain table: its cell relaxed under every sampled strain (sx, sa, sy), the displacement "
        "of each cell vertex recorded (T.npy + T.axes.txt; see docs/deformation.md)");
    c.command->add_option("--pattern", c.pattern, "Pattern file (.pyp / .json) or built-in name")
        ->capture_default_str();
    c.command->add_option("-o,--output", c.output, "Table file to write (.npy; its axes go to .axes.txt beside it)")
        ->required();
    c.command->add_option("--samples", c.samples, "Samples along sx, sa and sy (default 9 9 9)")->expected(3);
    c.command->add_option("--sx-range", c.sxRange, "Smallest and largest sx (default -0.2 1.0)")->expected(2);
    c.command->add_option("--sa-range", c.saRange, "Smallest and largest sa (default -0.7 0.7)")->expected(2);
    c.command->add_option("--sy-range", c.syRange, "Smallest and largest sy (default -0.2 1.0)")->expected(2);
    c.command
        ->add_option("--iterations", c.maxIterations, "Largest relaxation iteration count per sample (default 600)")
        ->check(CLI::Range(1, 1000000));
    c.command->add_flag("-q,--quiet", c.quiet,
                        "Quiet: print nothing but errors (no estimate, progress or summary on stderr)");
}

StrainTableOptions strainTableOptions(const StrainTableCommand& c) {
    StrainTableOptions o;
    if (!c.samples.empty()) o.samples = {c.samples[0], c.samples[1], c.samples[2]};
    if (!c.sxRange.empty()) o.sxRange = {c.sxRange[0], c.sxRange[1]};
    if (!c.saRange.empty()) o.saRange = {c.saRange[0], c.saRange[1]};
    if (!c.syRange.empty()) o.syRange = {c.syRange[0], c.syRange[1]};
    if (c.maxIterations > 0) o.maxIterations = c.maxIterations;
    return o;
}

StrainTable makeTableWithProgress(const Pattern& pattern, const StrainTableOptions& options, bool quiet,
                                  StrainTableStats& stats) {
    const size_t total = size_t(options.samples[0]) * size_t(options.samples[1]) * size_t(options.samples[2]);
    if (!quiet)
        std::fprintf(stderr,
                     "knit: strain table of %s (%zu cell vertices): %zu samples, estimated %.0f s on this machine\n",
                     pattern.name.c_str(), pattern.points.size(), total, estimateStrainTableSeconds(pattern, options));
    const InterruptGuard interrupt;
    StrainTableOptions o = options;
    size_t shown = 0;
    o.progress = [&](size_t done, size_t all) {
        interrupt.check();
        if (quiet || (done * 20 / all == shown && done != all)) return;
        shown = done * 20 / all;
        std::fprintf(stderr, "[%zu/%zu] strain samples\n", done, all);
    };
    StrainTable t = makeStrainTable(pattern, o, &stats);
    interrupt.check();
    return t;
}

int runStrainTable(const StrainTableCommand& c) {
    const Pattern pattern = loadPatternFileOrName(c.pattern);
    requireWritableFolder(c.output, "the strain table");  // before the long work
    refuseCollidingPaths({{"--pattern", c.pattern}},
                         {{"-o", c.output}, {"the table's axes file", strainAxesPath(c.output)}});
    // After the collisions (an output onto an input is the more useful message).
    refuseOtherFormatName("-o", c.output, "a strain table", ".npy");
    StrainTableStats stats;
    const StrainTable t = makeTableWithProgress(pattern, strainTableOptions(c), c.quiet, stats);
    writeStrainTable(t, c.output);
    if (!c.quiet)
        std::fprintf(stderr,
                     "knit: wrote %s and %s: %zu samples in %.1f s (%zu stopped at the iteration cap), closest yarns "
                     "%.2f radii\n",
                     c.output.c_str(), strainAxesPath(c.output).c_str(), t.samples(), stats.seconds, stats.unconverged,
                     stats.minDistance);
    return 0;
}

void printStrainTableInfo(const StrainTable& t, bool json) {
    double largest = 0, twist = 0;  // the largest |displacement| and |twist| anywhere in the table
    for (size_t i = 0; i < t.data.size(); ++i) {
        double& m = i % 4 == 3 ? twist : largest;
        m = std::max(m, double(std::abs(t.data[i])));
    }
    if (json) {
        nlohmann::json j = {{"strain_table", t.source},
                            {"vertices", t.vertexCount},
                            {"samples", {t.axes[0].size(), t.axes[1].size(), t.axes[2].size()}},
                            {"sx", t.axes[0]},
                            {"sa", t.axes[1]},
                            {"sy", t.axes[2]},
                            {"largest_displacement", largest},
                            {"largest_twist", twist}};
        if (t.px > 0) j["pattern"] = {{"name", t.pattern}, {"period", {t.px, t.py}}, {"radius", t.radius}};
        std::cout << j.dump(2) << '\n';
        return;
    }
    std::printf("strain table  %s\n", t.source.c_str());
    if (t.px > 0)
        std::printf("pattern       %s, period %.9g x %.9g m, radius %.9g m\n", t.pattern.c_str(), t.px, t.py, t.radius);
    else std::printf("pattern       (not recorded: a MADYPG table; only its vertex count is checked)\n");
    std::printf("vertices      %zu\nsamples       %zu x %zu x %zu (sx, sa, sy)\n", t.vertexCount, t.axes[0].size(),
                t.axes[1].size(), t.axes[2].size());
    const char* names[3] = {"sx", "sa", "sy"};
    for (size_t a = 0; a < 3; ++a) std::printf("%-13s [%.6g, %.6g]\n", names[a], t.axes[a].front(), t.axes[a].back());
    std::printf("largest |d|   %.6g (pattern units)\n", largest);
    std::printf("largest twist %.6g rad%s\n", twist, twist > 0 ? " (added to the ply phase)" : "");
}

}  // namespace knit::cli
