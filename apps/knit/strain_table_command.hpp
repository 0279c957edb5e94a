// strain_table_command.hpp — `knit strain-table`: a pattern's strain table (knit/strain.hpp) made
// by relaxing its cell under each sampled strain, with an estimate first and progress, written
// atomically as T.npy + T.axes.txt.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "knit/strain.hpp"

namespace knit::cli {

struct StrainTableCommand {
    CLI::App* command = nullptr;  // set by addStrainTableCommand
    std::string pattern = "stockinette";
    std::string output;
    std::vector<int> samples;  // empty or NX NA NY
    std::vector<double> sxRange, saRange, syRange;
    int maxIterations = 0;  // 0: the default
    bool quiet = false;
};

void addStrainTableCommand(CLI::App& app, StrainTableCommand& c);
int runStrainTable(const StrainTableCommand& c);

// The table options the flags ask for (shared with --deform strain, which makes a table on the spot).
StrainTableOptions strainTableOptions(const StrainTableCommand& c);
// Makes the table with the estimate and progress on stderr (unless quiet); Ctrl-C stops it.
StrainTable makeTableWithProgress(const Pattern& pattern, const StrainTableOptions& options, bool quiet,
                                  StrainTableStats& stats);

// Prints a table's description (`knit info T.npy` / `knit info sxsasy/`).
void printStrainTableInfo(const StrainTable& t, bool json);

}  // namespace knit::cli
