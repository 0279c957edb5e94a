// atomic_file.cpp — temporary sibling file + rename, so a failed export leaves no partial file.
#include "atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "knit/error.hpp"
#include "knit/output_file.hpp"
#include "stale_temporaries.hpp"
#include "temp_registry.hpp"

namespace knit::impl {
namespace fs = std::filesystem;

namespace {

constexpr size_t kStreamBuffer = size_t(1) << 20;

std::string folderOf(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

// The longest file name the folder's filesystem takes (NAME_MAX, 255 on every Linux filesystem
// libknit is used on; pathconf tells when the folder exists).
size_t nameMax(const std::string& folder) {
    const long n = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    return n > 16 ? size_t(n) : size_t(255);
}

// Unique per process and call: <folder>/.<name>.<pid>.<n>.tmp. The name is shortened so that
// the temporary's name stays within the filesystem's limit (a 240-byte output name is valid, its
// temporary's 260 bytes were not); the pid and counter keep it unique, and stale_temporaries
// reads them from the end.
std::string tempSibling(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(path);
    const std::string tail = "." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1)) + ".tmp";
    std::string name = p.filename().string();
    const size_t room = nameMax(folderOf(path)) - tail.size() - 1;
    if (name.size() > room) name.resize(room);
    return (p.parent_path() / ("." + name + tail)).string();
}

}  // namespace

void checkOutputFolder(const std::string& path) {
    if (path.empty()) throw Error("cannot write: no output path given");
    const fs::path p(path);
    if (!p.has_filename() || p.filename() == "." || p.filename() == "..")
        throw Error("cannot write '" + path + "': the path names a folder, not a file");
    requireWritableFolder(path);
    const size_t nameBytes = p.filename().string().size();
    if (nameBytes > nameMax(folderOf(path)))
        throw Error("cannot write '" + path + "': its file name is " + std::to_string(nameBytes) +
                    " bytes long, more than the folder's filesystem allows (" +
                    std::to_string(nameMax(folderOf(path))) + "); choose a shorter name");
    std::error_code ec;
    if (fs::is_directory(fs::status(path, ec)))
        throw Error("cannot write '" + path + "': a folder with that name exists");
    // The final rename would replace a device or FIFO node (or fail half-way): refuse it.
    const fs::file_status st = fs::status(path, ec);
    if (fs::exists(st) && !fs::is_regular_file(st))
        throw Error("cannot write '" + path + "': it exists and is not a regular file (a device, FIFO or socket)");
}

AtomicFile::AtomicFile(const std::string& path, bool binary) : path_(path) {
    checkOutputFolder(path);
    removeStaleTemporariesOnce(fs::path(path).parent_path().string());  // left by killed runs
    temp_ = tempSibling(path);
    registrySlot_ = registerTempFile(temp_);  // before it exists: no window where a signal leaks it
    buffer_.reset(new char[kStreamBuffer]);
    out_.rdbuf()->pubsetbuf(buffer_.get(), kStreamBuffer);
    errno = 0;
    out_.open(temp_, binary ? std::ios::out | std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
    if (!out_) {
        const int err = errno;
        unregisterTempFile(registrySlot_);
        throw Error("cannot write '" + path + "': cannot create a file in folder '" + folderOf(path) + "'" +
                    (err ? std::string(" (") + std::strerror(err) + ")" : std::string()));
    }
    lockFd_ = lockTemporary(temp_);
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        if (out_.is_open()) out_.close();
        std::error_code ec;
        fs::remove(temp_, ec);
    }
    unregisterTempFile(registrySlot_);
    unlockTemporary(lockFd_);
}

void AtomicFile::close() {
    if (closed_) return;
    closed_ = true;
    out_.flush();
    out_.seekp(0, std::ios::end);  // the size, also after a writer seeked back to patch a header
    const bool ok = static_cast<bool>(out_);
    size_ = ok ? static_cast<uint64_t>(out_.tellp()) : 0;
    out_.close();
    if (!ok || out_.fail()) throw Error("cannot write '" + path_ + "': writing failed (disk full or I/O error)");
}

uint64_t AtomicFile::bytesWritten() {
    if (closed_) return size_;
    return static_cast<uint64_t>(out_.tellp());
}

void AtomicFile::commit() {
    close();
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        throw Error("cannot write '" + path_ + "': renaming the finished file failed (" + std::strerror(err) + ")");
    }
    committed_ = true;
    unregisterTempFile(registrySlot_);
    registrySlot_ = -1;
    unlockTemporary(lockFd_);
    lockFd_ = -1;
}

void AtomicFile::undoCommit() {
    if (!committed_) return;
    std::error_code ec;
    fs::remove(path_, ec);
    committed_ = false;
}

void appendFile(std::ostream& out, const std::string& from, uint64_t offset, uint64_t bytes) {
    std::ifstream in(from, std::ios::binary);
    if (!in) throw Error("cannot reopen temporary file '" + from + "'");
    in.seekg(std::streamoff(offset));
    std::unique_ptr<char[]> block(new char[kStreamBuffer * 4]);
    uint64_t copied = 0;
    while (copied < bytes && in) {
        const uint64_t want = std::min<uint64_t>(bytes - copied, kStreamBuffer * 4);
        in.read(block.get(), std::streamsize(want));
        const std::streamsize got = in.gcount();
        if (got <= 0) break;
        out.write(block.get(), got);
        copied += uint64_t(got);
    }
    if (copied != bytes)
        throw Error("the temporary file '" + from + "' ended after " + std::to_string(copied) + " of " +
                    std::to_string(bytes) + " bytes");
}

}  // namespace knit::impl

namespace knit {
namespace fs = std::filesystem;

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
    impl::AtomicFile file(path, binary);  // throws naming the path (missing / unwritable folder)
    write(file.stream());                 // an exception here removes the temporary file
    file.commit();
}

void requireWritableFolder(const std::string& path, const std::string& what) {
    const std::string folder = impl::folderOf(path);
    const std::string cannot = "cannot write " + (what.empty() ? std::string() : what + " ") + "'" + path + "': ";
    std::error_code ec;
    const fs::file_status st = fs::status(folder, ec);
    if (!fs::exists(st)) throw Error(cannot + "folder '" + folder + "' does not exist");
    if (!fs::is_directory(st)) throw Error(cannot + "'" + folder + "' is not a folder");
    if (::access(folder.c_str(), W_OK) != 0) throw Error(cannot + "folder '" + folder + "' is not writable");
}

size_t removeStaleTemporaries(const std::string& folder) { return impl::removeStaleTemporaries(folder); }

}  // namespace knit
