// temp_registry.hpp (internal) — the temporary files being written right now, so that SIGINT or
// SIGTERM during an export removes them (and staging folders with their files): a signal-safe registry of live temporary paths and a
// handler that unlinks them, then re-raises the signal with its previous disposition.
#pragma once
#include <string>

namespace knit::impl {

// Registers `path` (installs the SIGINT/SIGTERM handler on first use); returns its slot, or -1
// when every slot is taken (the file is then only removed on normal exit paths).
int registerTempFile(const std::string& path);
// Registers a staging folder (OutputTransaction): the handler removes the files in it, then
// the folder. Same slots and return value as registerTempFile.
int registerTempFolder(const std::string& path);
// Forgets the slot (after the file was renamed or removed); -1 is ignored.
void unregisterTempFile(int slot);

}  // namespace knit::impl
