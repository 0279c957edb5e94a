// export_flags.hpp — the export flags of `knit build` (--export, --sides, --draco, ...).
#pragma once
#include <CLI/CLI.hpp>

#include "knit/export.hpp"
#include "knit/output_transaction.hpp"

namespace knit::cli {

// Registers --export --tubes-of --sides --no-caps --draco --draco-bits --draco-level --quantize
// --meshopt --yarn-colors --chunk-vertices --pretty-json (help group "Export") filling `options`.
void addExportFlags(CLI::App& command, ExportOptions& options);

// The options a command exports with: -o staged in `outputs` (committed with the other outputs)
// and the command's memory budget (--max-memory).
ExportOptions stagedExport(const ExportOptions& flags, const MemoryBudget& budget, OutputTransaction& outputs);

}  // namespace knit::cli
