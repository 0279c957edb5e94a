// output_transaction.cpp — staging folders next to the outputs, renamed together on commit (see
// knit/output_transaction.hpp).
#include "knit/output_transaction.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/stale_temporaries.hpp"
#include "io/temp_registry.hpp"

namespace knit {
namespace fs = std::filesystem;

namespace {

// One staged file: where it is, where it goes, and the hard link keeping the file it replaces.
struct Move {
    std::string from, to, backup;
};

std::string join(const std::string& folder, const std::string& name) {
    return folder.empty() ? name : (fs::path(folder) / name).string();
}

// Every staged file, with a backup name (in its staging folder) for a file it replaces.
std::vector<Move> plannedMoves(const std::string& staging, const std::string& final) {
    std::vector<Move> moves;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(staging, ec)) {
        const std::string name = e.path().filename().string();
        moves.push_back({e.path().string(), join(final, name), join(staging, ".previous." + name)});
    }
    return moves;
}

// Renames the moves in order; on failure puts back the ones done and throws naming the file.
void renameAll(std::vector<Move>& moves) {
    for (size_t k = 0; k < moves.size(); ++k) {
        Move& m = moves[k];
        // Step 1: keep the file it replaces (a hard link; none when there is no file or no link).
        if (::link(m.to.c_str(), m.backup.c_str()) != 0) m.backup.clear();
        // Step 2: the rename; on failure, restore every file renamed so far.
        if (std::rename(m.from.c_str(), m.to.c_str()) == 0) continue;
        const int err = errno;
        for (size_t j = k + 1; j-- > 0;) {
            const Move& done = moves[j];
            if (j < k) {
                if (!done.backup.empty()) std::rename(done.backup.c_str(), done.to.c_str());
                else ::unlink(done.to.c_str());
            } else if (!done.backup.empty()) {
                ::unlink(done.backup.c_str());
            }
        }
        throw Error("cannot write '" + m.to + "': renaming the finished file failed (" + std::strerror(err) +
                    "); no output was changed");
    }
}

}  // namespace

OutputTransaction::~OutputTransaction() { removeStaging(); }

const OutputTransaction::Folder& OutputTransaction::folderFor(const std::string& finalFolder) {
    for (const Folder& f : folders_)
        if (f.final == finalFolder) return f;
    impl::removeStaleTemporariesOnce(finalFolder);  // staging folders of killed runs
    static std::atomic<unsigned> counter{0};
    Folder f;
    f.final = finalFolder;
    f.staging = join(finalFolder, ".knit-staging." + std::to_string(::getpid()) + "." +
                                      std::to_string(counter.fetch_add(1)) + ".tmp");
    f.registrySlot = impl::registerTempFolder(f.staging);  // before it exists: a signal never leaks it
    std::error_code ec;
    if (!fs::create_directory(f.staging, ec) || ec) {
        impl::unregisterTempFile(f.registrySlot);
        throw Error("cannot write into folder '" + (finalFolder.empty() ? std::string(".") : finalFolder) +
                    "': cannot create a temporary folder there (" + ec.message() + ")");
    }
    f.lockFd = impl::lockTemporary(f.staging);  // released only when the folder is gone (or the process)
    folders_.push_back(f);
    return folders_.back();
}

std::string OutputTransaction::stage(const std::string& finalPath) {
    if (finalPath.empty()) return finalPath;
    impl::checkOutputFolder(finalPath);
    // Two outputs of one command onto one name in one folder: the later rename would replace the
    // earlier file. The folder is resolved (symlinks, ".."), the name is not: rename() replaces
    // a symlink itself, not its target.
    const fs::path p(finalPath);
    std::error_code absoluteError, canonicalError;
    const fs::path absolute = fs::absolute(p.parent_path().empty() ? "." : p.parent_path(), absoluteError);
    const fs::path folder = fs::weakly_canonical(absolute, canonicalError);
    const std::string identity = absoluteError || canonicalError ? finalPath : (folder / p.filename()).string();
    for (const auto& [given, known] : staged_)
        if (known == identity)
            throw Error("'" + finalPath + "' is named for two outputs of this command" +
                        (given != finalPath ? " (also as '" + given + "')" : std::string()) +
                        "; give each output its own path");
    std::string staged = join(folderFor(p.parent_path().string()).staging, p.filename().string());
    staged_.emplace_back(finalPath, identity);
    return staged;
}

void OutputTransaction::commit() {
    std::vector<Move> moves;
    for (const Folder& f : folders_)
        for (Move& m : plannedMoves(f.staging, f.final)) moves.push_back(std::move(m));
    renameAll(moves);
    removeStaging();  // now only the hard links to the replaced files
    staged_.clear();
}

std::string OutputTransaction::finalNames(std::string text) const {
    for (const Folder& f : folders_) {
        const std::string from = f.staging + "/", to = f.final.empty() ? std::string() : f.final + "/";
        for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
            text.replace(at, from.size(), to);
    }
    return text;
}

void OutputTransaction::removeStaging() {
    for (Folder& f : folders_) {
        std::error_code ec;
        fs::remove_all(f.staging, ec);
        impl::unregisterTempFile(f.registrySlot);
        f.registrySlot = -1;
        impl::unlockTemporary(f.lockFd);
        f.lockFd = -1;
    }
    folders_.clear();
}

}  // namespace knit
