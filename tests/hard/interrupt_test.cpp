// Interrupts (docs/hard-cases.md, "Interrupts"): SIGTERM or SIGINT during an export removes the
// temporary file; no output is left and the CLI ends by the signal.
#ifdef KNIT_HARD_HAVE_CLI
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

// Whether `d` holds a file whose name ends with `.tmp`.
bool hasTempFile(const fs::path& d) {
    for (const auto& e : fs::directory_iterator(d))
        if (e.path().extension() == ".tmp") return true;
    return false;
}

// Starts a big export in `d`, sends `sig` once its temporary file exists, returns the wait status.
int interruptedExport(const fs::path& d, int sig) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (::chdir(d.c_str()) != 0) ::_exit(127);
        ::execl(knit::test::knitCli(), knit::test::knitCli(), "build", "-q", "--mesh", "plane", "--repeats", "300",
                "300", "--export", "tubes", "--sides", "64", "-o", "big.obj", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!hasTempFile(d) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_TRUE(hasTempFile(d)) << "the export never created its temporary file";
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // mid-write
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

class Interrupts : public ::testing::TestWithParam<int> {};

TEST_P(Interrupts, signalDuringAnExportRemovesTheTemporaryFile) {
    knit::test::TempDir tmp;
    const int status = interruptedExport(tmp.path(), GetParam());
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == GetParam()) << "status " << status;
    EXPECT_FALSE(hasTempFile(tmp.path()));
    EXPECT_FALSE(fs::exists(tmp.path() / "big.obj"));
}

INSTANTIATE_TEST_SUITE_P(Hard, Interrupts, ::testing::Values(SIGTERM, SIGINT),
                         [](const ::testing::TestParamInfo<int>& i) {
                             return i.param == SIGTERM ? "SIGTERM" : "SIGINT";
                         });

}  // namespace
#endif  // KNIT_HARD_HAVE_CLI
