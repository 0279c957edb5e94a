// temp_folder.hpp — the server's own temporary folder: every file it writes goes here under a
// name it chose, and the folder goes when the server stops.
#pragma once
#include <atomic>
#include <string>

namespace knit::serve {

class TempFolder {
public:
    // A new folder "knit-serve-XXXXXX" in $TMPDIR (else /tmp); throws knit::Error when it cannot.
    TempFolder();
    ~TempFolder();  // removes the folder and everything in it
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    const std::string& path() const { return path_; }
    // A fresh file path in the folder: "<prefix>-<n>.<extension>".
    std::string newFile(const std::string& prefix, const std::string& extension);

private:
    std::string path_;
    std::atomic<unsigned> next_{0};
};

// The bytes of a file the server wrote; false when it cannot be read.
bool readWholeFile(const std::string& path, std::string& bytes);

}  // namespace knit::serve
