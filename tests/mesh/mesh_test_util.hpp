// mesh_test_util.hpp — small helpers for the mesh tests: a per-test temporary folder and
// file writers (inputs are generated in code, never copied from elsewhere).
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <unistd.h>

#include "knit/error.hpp"

namespace knit_test {

// A fresh folder under the system temp dir, named after the running test; removed at the end.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("knit_mesh_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                 std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    std::string write(const std::string& name, const std::string& content) const {
        const std::string p = file(name);
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// The message of the knit::Error that `f` throws, or "(no knit::Error thrown)".
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const knit::Error& e) {
        return e.what();
    }
    return "(no knit::Error thrown)";
}

}  // namespace knit_test
