// Temporaries of killed runs: a writer removes, in the folder it writes to, the temporary files
// and staging folders of processes that are gone, and nothing else (a live process's, another
// user's, a locked one, a name that is not ours).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include "io/stale_temporaries.hpp"
#include "knit/output_file.hpp"
#include "knit/output_transaction.hpp"
#include "test_util.hpp"

namespace {

namespace fs = std::filesystem;
using knit::impl::parseTemporaryName;
using knit::impl::removeStaleTemporaries;

std::vector<std::string> namesIn(const fs::path& d) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(d)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

// A process id that was just used and is gone (a child that exited and was reaped).
pid_t deadPid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    ::waitpid(pid, nullptr, 0);
    return pid;
}

// Whether someone holds the lock of `path` (a temporary in use).
bool isLocked(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    const bool locked = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    ::close(fd);
    return locked;
}

TEST(StaleTemporaries, onlyOurNamesWithAProcessIdAreTemporaries) {
    const auto staging = parseTemporaryName(".knit-staging.4242.7.tmp");
    ASSERT_TRUE(staging);
    EXPECT_TRUE(staging->stagingFolder);
    EXPECT_EQ(staging->pid, 4242);
    const auto file = parseTemporaryName(".c.pc2.4242.0.tmp");
    ASSERT_TRUE(file);
    EXPECT_FALSE(file->stagingFolder);
    EXPECT_EQ(file->pid, 4242);
    for (const char* name :
         {"c.pc2.4242.0.tmp", ".4242.0.tmp", "..4242.0.tmp", ".c.pc2.4242.0", ".c.pc2.42x.0.tmp", ".c.pc2.4242..tmp",
          ".notes.tmp", ".knit-staging.abc.tmp", ".knit-staging.1.0.tmp", ".c.99999999999.0.tmp", ".c.0.0.tmp"})
        EXPECT_FALSE(parseTemporaryName(name)) << name;
}

TEST(StaleTemporaries, onlyThoseOfDeadProcessesOfThisUserNobodyLocksAreRemoved) {
    knit::test::TempDir tmp;
    const std::string dead = std::to_string(deadPid());
    const pid_t liveChild = ::fork();
    if (liveChild == 0) {
        ::pause();
        ::_exit(0);
    }
    const std::string live = std::to_string(liveChild);
    // Removed: a dead run's staging folder (with its partial file) and its temporary file.
    fs::create_directory(tmp.path() / (".knit-staging." + dead + ".0.tmp"));
    tmp.write(".knit-staging." + dead + ".0.tmp/.c.pc2." + dead + ".1.tmp", "partial");
    tmp.write(".out.obj." + dead + ".2.tmp", "partial");
    // Kept: a live process's, a locked one (a process of another machine or PID namespace),
    // wrong kinds and names that are not ours, the user's files.
    fs::create_directory(tmp.path() / (".knit-staging." + live + ".0.tmp"));
    tmp.write(".out.obj." + live + ".3.tmp", "writing");
    const std::string locked = tmp.write(".locked.obj." + dead + ".4.tmp", "writing elsewhere");
    const int lock = knit::impl::lockTemporary(locked);
    ASSERT_GE(lock, 0);
    tmp.write(".knit-staging." + dead + ".5.tmp", "a file, not a staging folder");
    fs::create_directory(tmp.path() / (".dir." + dead + ".6.tmp"));
    tmp.write(".notes.tmp", "mine");
    tmp.write("c.pc2", "mine");
    std::vector<std::string> kept = namesIn(tmp.path());
    if (::geteuid() == 0) {  // another user's dead run: only root can make one here
        const std::string foreign = tmp.write(".foreign.obj." + dead + ".7.tmp", "theirs");
        ASSERT_EQ(::chown(foreign.c_str(), 65534, 65534), 0);
        kept = namesIn(tmp.path());
    }
    kept.erase(std::remove(kept.begin(), kept.end(), ".knit-staging." + dead + ".0.tmp"), kept.end());
    kept.erase(std::remove(kept.begin(), kept.end(), ".out.obj." + dead + ".2.tmp"), kept.end());

    EXPECT_EQ(removeStaleTemporaries(tmp.path().string()), 2u);
    EXPECT_EQ(namesIn(tmp.path()), kept);
    // Once the lock is released and the live process is gone, theirs go too.
    knit::impl::unlockTemporary(lock);
    ::kill(liveChild, SIGKILL);
    ::waitpid(liveChild, nullptr, 0);
    EXPECT_EQ(removeStaleTemporaries(tmp.path().string()), 3u);
    EXPECT_FALSE(fs::exists(tmp.path() / (".knit-staging." + live + ".0.tmp")));
    EXPECT_FALSE(fs::exists(tmp.path() / (".out.obj." + live + ".3.tmp")));
    EXPECT_FALSE(fs::exists(locked));
    EXPECT_TRUE(fs::exists(tmp.path() / "c.pc2"));
}

TEST(StaleTemporaries, writersLockTheirTemporariesAndSweepTheFolderTheyWriteTo) {
    knit::test::TempDir tmp;
    const std::string dead = std::to_string(deadPid());
    fs::create_directory(tmp.path() / (".knit-staging." + dead + ".0.tmp"));
    tmp.write(".a.txt." + dead + ".1.tmp", "partial");
    fs::create_directory(tmp.path() / "sub");
    tmp.write("sub/.knit-staging." + dead + ".2.tmp", "a file: not ours");
    fs::create_directory(tmp.path() / ("sub/.knit-staging." + dead + ".3.tmp"));
    {
        knit::OutputTransaction outputs;
        const std::string staged = outputs.stage(tmp.file("sub/b.txt"));
        EXPECT_TRUE(isLocked(fs::path(staged).parent_path().string()));  // the staging folder is in use
        knit::writeFileAtomically(
            staged,
            [&](std::ostream& out) {
                out << "B";
                for (const auto& e : fs::directory_iterator(fs::path(staged).parent_path()))
                    EXPECT_TRUE(isLocked(e.path().string())) << e.path();  // the temporary file too
            },
            false);
        outputs.commit();
    }
    EXPECT_EQ(namesIn(tmp.path() / "sub"), (std::vector<std::string>{".knit-staging." + dead + ".2.tmp", "b.txt"}));
    knit::writeFileAtomically(
        tmp.file("a.txt"), [](std::ostream& out) { out << "A"; }, false);
    EXPECT_EQ(namesIn(tmp.path()), (std::vector<std::string>{"a.txt", "sub"}));
}

}  // namespace
