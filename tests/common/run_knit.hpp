// Runs the `knit` command line (test_paths.hpp) in a folder and
// captures its exit code and combined stdout/stderr; shared by the CLI-level tests.
#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include "common/test_paths.hpp"

namespace knit::test {

struct CliRun {
    int exitCode = -1;
    std::string output;  // stdout + stderr
};

inline CliRun runKnit(const std::string& args, const std::filesystem::path& cwd) {
    const std::string cmd = "cd '" + cwd.string() + "' && '" + test::knitCli() + "' " + args + " 2>&1";
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, n);
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace knit::test
