// knit/output_transaction.hpp — several output files committed together: nothing that exists is
// touched until every new file is complete.
//
// A command that writes several files (an export and its report, a PNG and an EXR, point caches
// and their topology) stages each one: stage(path) names the same file in a hidden staging folder
// next to it (same filesystem), the writers write there (a .gltf's .bin files land beside it
// under their final names), and commit() renames every staged file onto its folder at the end.
// If a step fails before commit(), the destructor removes the staging folders and every
// pre-existing output is unchanged; SIGINT / SIGTERM remove them too, and a run killed outright
// (SIGKILL, power loss) leaves them to the next run writing into that folder, which removes the
// staging folders of processes that are gone (internal io/stale_temporaries.hpp). If a rename in commit()
// fails, the files renamed before it are put back (the previous files restored from hard links).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "knit/error.hpp"

namespace knit {

class OutputTransaction {
public:
    OutputTransaction() = default;
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    // Where to write `finalPath` now ("" stays ""). Checks the final path first (its folder exists
    // and is writable, it is not a folder or a device, it was not staged before under this or
    // another name of the same file): knit::Error naming it.
    std::string stage(const std::string& finalPath);

    // Renames every file in the staging folders onto its final folder; throws knit::Error naming
    // the file when a rename fails (after restoring the files renamed before it).
    void commit();

    // `text` with every staging folder replaced by its final folder (for messages).
    std::string finalNames(std::string text) const;

    // Runs `step` (a writer given staged paths); a knit::Error it throws is re-thrown with the
    // final names, so messages never show the staging folder.
    template <class Step>
    auto run(Step&& step) -> decltype(step()) {
        try {
            return std::forward<Step>(step)();
        } catch (const Error& e) {
            throw Error(finalNames(e.what()));
        }
    }

private:
    struct Folder {
        std::string final;    // the outputs' folder as given ("" for the working folder)
        std::string staging;  // <final>/.knit-staging.<pid>.<n>.tmp
        int registrySlot = -1;
        int lockFd = -1;  // holds the folder's lock: it is in use (io/stale_temporaries.hpp)
    };
    const Folder& folderFor(const std::string& finalFolder);
    void removeStaging();

    std::vector<Folder> folders_;
    std::vector<std::pair<std::string, std::string>> staged_;  // final path as given, its canonical form
};

}  // namespace knit
