// stale_temporaries.cpp — finds and removes the temporaries of killed runs (see stale_temporaries.hpp).
#include "stale_temporaries.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <climits>
#include <filesystem>
#include <mutex>
#include <set>
#include <system_error>

namespace knit::impl {
namespace fs = std::filesystem;

namespace {

const std::string kStagingPrefix = ".knit-staging.";
const std::string kSuffix = ".tmp";

// Parses "<pid>.<n>" (both plain decimal numbers); the pid must be one a process can have.
std::optional<long> pidOf(const std::string& numbers) {
    const size_t dot = numbers.find('.');
    if (dot == 0 || dot == std::string::npos || dot + 1 == numbers.size()) return std::nullopt;
    for (size_t i = 0; i < numbers.size(); ++i)
        if (i != dot && (numbers[i] < '0' || numbers[i] > '9')) return std::nullopt;
    if (dot > 10) return std::nullopt;
    const long pid = std::stol(numbers.substr(0, dot));
    if (pid <= 1 || pid > INT_MAX) return std::nullopt;
    return pid;
}

// Whether the process `pid` is gone on this machine (a process of another user still exists: EPERM).
bool processIsGone(long pid) { return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH; }

// Whether nobody holds the temporary's lock; the lock is released again before returning, and the
// caller removes the entry right after (a writer that started since holds a new name).
bool lockIsFree(const std::string& path, bool folder) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | (folder ? O_DIRECTORY : 0));
    if (fd < 0) return false;
    const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    ::close(fd);
    return free;
}

// Whether the entry `name` in `folder` is a temporary of a dead process of this user, nobody's lock on it.
bool isStale(const fs::path& path, const TemporaryName& t) {
    if (t.pid == long(::getpid())) return false;
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || st.st_uid != ::geteuid()) return false;
    if (t.stagingFolder ? !S_ISDIR(st.st_mode) : !S_ISREG(st.st_mode)) return false;
    return processIsGone(t.pid) && lockIsFree(path.string(), t.stagingFolder);
}

}  // namespace

std::optional<TemporaryName> parseTemporaryName(const std::string& name) {
    if (name.size() <= kSuffix.size() + 1 || name[0] != '.' ||
        name.compare(name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0)
        return std::nullopt;
    const std::string stem = name.substr(0, name.size() - kSuffix.size());
    TemporaryName t;
    if (stem.compare(0, kStagingPrefix.size(), kStagingPrefix) == 0) {
        const std::optional<long> pid = pidOf(stem.substr(kStagingPrefix.size()));
        if (!pid) return std::nullopt;
        t.stagingFolder = true;
        t.pid = *pid;
        return t;
    }
    // .<name>.<pid>.<n>: the last two dots, with a non-empty name before them.
    const size_t last = stem.rfind('.');
    const size_t pidDot = last == std::string::npos || last == 0 ? std::string::npos : stem.rfind('.', last - 1);
    if (pidDot == std::string::npos || pidDot < 2) return std::nullopt;
    const std::optional<long> pid = pidOf(stem.substr(pidDot + 1));
    if (!pid) return std::nullopt;
    t.pid = *pid;
    return t;
}

int lockTemporary(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) return -1;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

void unlockTemporary(int fd) {
    if (fd >= 0) ::close(fd);
}

size_t removeStaleTemporaries(const std::string& folder) {
    const fs::path dir = folder.empty() ? fs::path(".") : fs::path(folder);
    size_t removed = 0;
    std::error_code ec;
    fs::directory_iterator it(dir, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        const fs::path path = it->path();
        const std::optional<TemporaryName> t = parseTemporaryName(path.filename().string());
        if (!t || !isStale(path, *t)) continue;
        std::error_code removeError;
        if (fs::remove_all(path, removeError) > 0 && !removeError) ++removed;
    }
    return removed;
}

void removeStaleTemporariesOnce(const std::string& folder) {
    static std::mutex mutex;
    static std::set<std::string> swept;
    std::error_code ec;
    const fs::path absolute = fs::absolute(folder.empty() ? fs::path(".") : fs::path(folder), ec);
    const std::string key = ec ? folder : absolute.lexically_normal().string();
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!swept.insert(key).second) return;
    }
    removeStaleTemporaries(folder);
}

}  // namespace knit::impl
