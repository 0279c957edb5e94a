// gltf_validator.hpp — runs the Khronos glTF-Validator (node + npm `gltf-validator`) from tests.
//
// The validator package is found at $KNIT_GLTF_VALIDATOR (the package folder), else at
// <build>/node/node_modules/gltf-validator (install: see README / validate_gltf.js). node is
// $KNIT_NODE or `node` on PATH. When it is missing the test is skipped locally, but FAILS when
// the environment variable CI is "true" (the CI must run every validation).
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include "common/test_paths.hpp"

namespace knit::test {

struct ValidatorReport {
    bool ran = false;  // false: validator unavailable (the test was skipped or failed)
    int errors = 0, warnings = 0, infos = 0, hints = 0;
    nlohmann::json report;  // the full validator report
    std::string messages;   // errors and warnings, one per line (for failure output)
    bool hasInfo(const std::string& code) const {
        if (!report.contains("issues") || !report["issues"].contains("messages")) return false;
        for (const auto& m : report["issues"]["messages"])
            if (m.value("code", "") == code) return true;
        return false;
    }
};

inline std::string validatorModuleDir() {
    if (const char* env = std::getenv("KNIT_GLTF_VALIDATOR"); env && *env) return env;
    return (std::filesystem::path(test::binaryDir()) / "node" / "node_modules" / "gltf-validator").string();
}

inline std::string nodeExecutable() {
    if (const char* env = std::getenv("KNIT_NODE"); env && *env) return env;
    return "node";
}

inline bool runningInCi() {
    const char* ci = std::getenv("CI");
    return ci && (std::string(ci) == "true" || std::string(ci) == "1");
}

inline std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'') out += "'\\''";
        else out += c;
    }
    return out + "'";
}

// Runs the validator; on success fills the counts. If the validator is not installed, records a
// failure under CI=true and otherwise marks the report as not run (caller should GTEST_SKIP).
inline ValidatorReport runGltfValidator(const std::string& file) {
    ValidatorReport r;
    const std::string module = validatorModuleDir();
    const std::string script = std::string(test::sourceDir()) + "/tests/export/validate_gltf.js";
    const bool nodeOk = std::system((nodeExecutable() + " --version > /dev/null 2>&1").c_str()) == 0;
    if (!nodeOk || !std::filesystem::exists(std::filesystem::path(module) / "package.json")) {
        const std::string why = "glTF-Validator not available (node: " + std::string(nodeOk ? "ok" : "missing") +
                                ", module: " + module +
                                "). Install: npm install --prefix <build>/node gltf-validator@2.0.0-dev.3.10";
        if (runningInCi()) ADD_FAILURE() << why << " — required because CI=true";
        else std::fprintf(stderr, "%s\n", why.c_str());
        return r;
    }
    const std::string out = file + ".validation.json";
    const std::string cmd = nodeExecutable() + " " + shellQuote(script) + " " + shellQuote(module) + " " +
                            shellQuote(file) + " > " + shellQuote(out);
    const int rc = std::system(cmd.c_str());
    if (rc != 0) {
        ADD_FAILURE() << "validator could not run on " << file << " (exit " << rc << ")";
        return r;
    }
    std::FILE* f = std::fopen(out.c_str(), "rb");
    std::string text;
    if (f) {
        char buf[65536];
        size_t n;
        while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) text.append(buf, n);
        std::fclose(f);
    }
    std::filesystem::remove(out);
    r.report = nlohmann::json::parse(text, nullptr, false);
    if (r.report.is_discarded() || !r.report.contains("issues")) {
        ADD_FAILURE() << "unreadable validator report for " << file << ": " << text.substr(0, 500);
        return r;
    }
    const auto& issues = r.report["issues"];
    r.errors = issues.value("numErrors", -1);
    r.warnings = issues.value("numWarnings", -1);
    r.infos = issues.value("numInfos", 0);
    r.hints = issues.value("numHints", 0);
    for (const auto& m : issues["messages"]) {
        if (m.value("severity", 3) <= 1)
            r.messages += m.value("code", "") + " at " + m.value("pointer", "") + ": " + m.value("message", "") + "\n";
    }
    r.ran = true;
    return r;
}

// Expects 0 errors and 0 warnings. Outside CI a missing validator skips the test (GTEST_SKIP
// from here returns only from this helper; assertions made before and after still count).
inline void expectGltfValid(const std::string& file, ValidatorReport* out = nullptr) {
    ValidatorReport r = runGltfValidator(file);
    if (out) *out = r;
    if (!r.ran) {
        if (!runningInCi()) GTEST_SKIP() << "glTF-Validator not installed";
        return;
    }
    EXPECT_EQ(r.errors, 0) << file << "\n" << r.messages;
    EXPECT_EQ(r.warnings, 0) << file << "\n" << r.messages;
}

}  // namespace knit::test
