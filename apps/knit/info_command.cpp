// `knit info`: load a pattern and print knit::describePattern, as text or JSON.
#include "info_command.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/strain.hpp"
#include "strain_table_command.hpp"

namespace knit::cli {
namespace {

void printJson(const Pattern& p, const PatternInfo& info) {
    const nlohmann::json j = {
        {"name", p.name},
        {"period", {info.px, info.py}},
        {"radius", info.radius},
        {"vertices", info.vertexCount},
        {"edges", info.edgeCount},
        {"crossings",
         {{"+x", info.crossings[0]}, {"-x", info.crossings[1]}, {"+y", info.crossings[2]}, {"-y", info.crossings[3]}}},
        {"loops_1x1", info.loops1x1},
        {"open_yarns_1x1", info.openYarns1x1}};
    std::cout << j.dump(2) << '\n';
}

void printText(const Pattern& p, const PatternInfo& info) {
    std::printf("pattern   %s\n", p.name.c_str());
    std::printf("period    %.9g x %.9g m\n", info.px, info.py);
    std::printf("radius    %.9g m\n", info.radius);
    std::printf("vertices  %zu\nedges     %zu\n", info.vertexCount, info.edgeCount);
    std::printf("crossing  +x %zu, -x %zu, +y %zu, -y %zu\n", info.crossings[0], info.crossings[1], info.crossings[2],
                info.crossings[3]);
    std::printf("bounds    x [%.6g, %.6g] y [%.6g, %.6g] z [%.6g, %.6g]\n", info.boundsMin.x, info.boundsMax.x,
                info.boundsMin.y, info.boundsMax.y, info.boundsMin.z, info.boundsMax.z);
    std::printf("1x1 periodic tiling: %zu closed loops, %zu open yarns\n", info.loops1x1, info.openYarns1x1);
}

}  // namespace

void addInfoCommand(CLI::App& app, InfoCommand& i) {
    i.command = app.add_subcommand(
        "info",
        "Describe a pattern (period, radius, counts, edges crossing each side, loops of a 1x1 tiling) or a strain "
        "table (.npy or a sxsasy/ folder)");
    i.command->add_option("pattern", i.pattern, "Pattern file (.pyp / .json), built-in name or strain table")
        ->required();
    i.command->add_flag("--json", i.json, "Print JSON");
}

namespace {
// A strain table: a .npy file, or a folder holding data.npy (MADYPG's sxsasy/).
bool isStrainTable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        return std::filesystem::exists(std::filesystem::path(path) / "data.npy", ec);
    return path.size() > 4 && path.compare(path.size() - 4, 4, ".npy") == 0;
}
}  // namespace

int runInfo(const InfoCommand& i) {
    if (isStrainTable(i.pattern)) {
        printStrainTableInfo(loadStrainTable(i.pattern), i.json);
        return 0;
    }
    const Pattern p = loadPatternFileOrName(i.pattern);
    const PatternInfo info = describePattern(p);
    if (i.json) printJson(p, info);
    else printText(p, info);
    return 0;
}

}  // namespace knit::cli
