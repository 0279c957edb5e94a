// atomic_file.hpp (internal) — output files written to a temporary sibling and renamed on commit.
#pragma once
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace knit::impl {

// A temporary file next to `path` (same folder, so the final rename is atomic). The destructor
// removes the temporary file unless commit() renamed it onto `path`; SIGINT / SIGTERM while it
// is open removes it too (temp_registry.hpp); while it exists it is locked, so a run killed
// outright leaves one a later writer to that folder removes (stale_temporaries.hpp). Errors name `path`.
class AtomicFile {
public:
    AtomicFile(const std::string& path, bool binary);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    const std::string& path() const { return path_; }
    const std::string& tempPath() const { return temp_; }
    // Flushes and closes; throws knit::Error if any write failed (disk full, I/O error).
    void close();
    // close() (if not done) then renames the temporary file onto the final path.
    void commit();
    // Removes the final file again (used when a later file of a multi-file output fails).
    void undoCommit();
    bool committed() const { return committed_; }
    uint64_t bytesWritten();

private:
    std::string path_;
    std::string temp_;
    std::ofstream out_;
    std::unique_ptr<char[]> buffer_;
    bool closed_ = false;
    bool committed_ = false;
    uint64_t size_ = 0;
    int registrySlot_ = -1;  // in the signal cleanup registry while the temporary file exists
    int lockFd_ = -1;        // holds the temporary file's lock (stale_temporaries.hpp)
};

// Checks that `path` names a file whose folder exists and is writable (knit::requireWritableFolder)
// and is not itself a folder; throws knit::Error naming it.
void checkOutputFolder(const std::string& path);

// Appends `bytes` bytes of file `from`, starting at `offset`, to `out`.
void appendFile(std::ostream& out, const std::string& from, uint64_t offset, uint64_t bytes);

}  // namespace knit::impl
