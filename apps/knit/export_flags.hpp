// export_flags.hpp — the export flags of `knit build` (--export, --sides, --draco, ...).
#pragma once
#include <CLI/CLI.hpp>

#include "knit/export.hpp"

namespace knit::cli {

// Registers --export --tubes-of --sides --no-caps --draco --draco-bits --draco-level --quantize
// --meshopt --yarn-colors --chunk-vertices --pretty-json (help group "Export") filling `options`.
void addExportFlags(CLI::App& command, ExportOptions& options);

}  // namespace knit::cli
