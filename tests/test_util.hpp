// test_util.hpp — helpers shared by every test area: a per-test temporary folder, whole-file
// reading and writing, and the message of a thrown knit::Error (include as "test_util.hpp").
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "knit/error.hpp"

namespace knit::test {

// A fresh folder under the system temp dir, named after the running test and the process
// (knit_<suite>_<test>_<pid>); removed with everything in it when the object goes away.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        const std::string test = info ? std::string(info->test_suite_name()) + "_" + info->name() : "no_test";
        path_ = std::filesystem::temp_directory_path() / ("knit_" + test + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    // Writes `content` to a new file `name` in the folder (binary) and returns its path.
    std::string write(const std::string& name, const std::string& content) const {
        const std::string p = file(name);
        std::filesystem::remove(p);  // a fresh file: rewriting through truncation makes ext4 flush (slow)
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }

private:
    std::filesystem::path path_;
};

inline std::vector<unsigned char> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The whole file as a string (read in binary: no newline translation).
inline std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
}

// The message of the knit::Error that `f` throws, or "(no knit::Error thrown)".
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const knit::Error& e) {
        return e.what();
    }
    return "(no knit::Error thrown)";
}

}  // namespace knit::test
