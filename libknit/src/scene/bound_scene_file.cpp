// bound_scene_file.cpp — a bound scene file's bytes for readBoundScene: a read-only private
// memory map of the whole file (the page cache's pages themselves: nothing is allocated or
// copied for the arrays a loaded scene uses in place), or, when the file cannot be mapped (a
// file system without mmap), the file read into memory allocated for it once. Either way the
// bytes have an owner (a shared_ptr), which the loaded scene's views share: the map stays open
// while the scene, a copy of it or an Animator of it lives.
//
// A map reads the file as it is now: a file truncated in place while a scene maps it makes the
// next read of a lost page fault (SIGBUS) and one rewritten in place changes the arrays under
// the scene. `knit bind` (writeBoundScene) replaces files by rename, which an open map survives
// (it keeps the old file); do not truncate or rewrite a bound scene file in place while it is in use.
#include "scene/bound_scene_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include "knit/bound_scene.hpp"
#include "knit/error.hpp"

namespace knit::impl {
namespace {

std::string cannotRead(const std::string& path, int error) {
    return "cannot read bound scene '" + path + "': " + std::strerror(error);
}

// Closes a file descriptor on every path out.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

// The whole file read into fresh memory (not zeroed first); `size` bytes are expected.
BoundSceneFile readWhole(int fd, const std::string& path, size_t size) {
    std::shared_ptr<char[]> buffer(new char[size]);
    size_t got = 0;
    while (got < size) {
        const ssize_t n = ::pread(fd, buffer.get() + got, size - got, static_cast<off_t>(got));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Error(cannotRead(path, errno));
        if (n == 0) throw Error(cannotRead(path, EIO) + " (it shrank while being read)");
        got += static_cast<size_t>(n);
    }
    return {buffer, std::string_view(buffer.get(), size), false};
}

}  // namespace

BoundSceneFile openBoundSceneFile(const std::string& path, const MemoryBudget& budget, BoundSceneAccess access) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error("cannot read bound scene '" + path + "': " + ec.message());
    budget.require(static_cast<double>(size), "reading bound scene '" + path + "'",
                   "the scene's size (bind fewer repeats)");
    const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
    if (file.fd < 0) throw Error(cannotRead(path, errno));
    if (size == 0) return {nullptr, std::string_view(), false};
    if (access == BoundSceneAccess::Map) {
        void* at = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, file.fd, 0);
        if (at != MAP_FAILED) {
            const std::shared_ptr<void> mapping(at, [size](void* map) { ::munmap(map, size); });
            return {mapping, std::string_view(static_cast<const char*>(at), size), true};
        }
    }
    return readWhole(file.fd, path, size);  // not mappable (or asked not to map)
}

}  // namespace knit::impl

namespace knit {

BoundScene readBoundScene(const std::string& path, const MemoryBudget& budget) {
    const impl::BoundSceneFile file = impl::openBoundSceneFile(path, budget);
    return decodeBoundScene(file.bytes, file.owner, path, budget);
}

}  // namespace knit
