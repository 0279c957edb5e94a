// common.hpp — what the speed-vs-error items share: wall and CPU time, the machine, the test
// scenes and the files they write (see main.cpp for the program).
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "knit/scene.hpp"
#include "util/math.hpp"

namespace sve {

using glm::dvec2;
using glm::dvec3;
using knit::util::kPi;
using nlohmann::json;
namespace fs = std::filesystem;

// ---- machine, timing ---------------------------------------------------------------------------

double seconds(std::chrono::steady_clock::time_point t0);
// The 1, 5 and 15 minute load averages (/proc/loadavg), and the same as a JSON array.
std::array<double, 3> loadAverage();
json loadJson();
// Process CPU time (user + system, all threads) in seconds.
double cpuSeconds();
std::string cpuModel();
// Installed memory (physical pages x page size, i.e. MemTotal) in bytes; 0 if unavailable.
size_t memTotalBytes();

struct Timing {
    double best = 0, median = 0;
    int runs = 0;
};
json timingJson(const Timing& t);

// Runs f at least minRuns and at most maxRuns times, stopping after budget seconds in total;
// `setup` runs untimed before every run (e.g. removing the previous output file).
template <class S, class F>
Timing timeRunsWithSetup(S&& setup, F&& f, int minRuns, int maxRuns, double budget) {
    std::vector<double> t;
    double total = 0;
    while (int(t.size()) < maxRuns && (int(t.size()) < minRuns || total < budget)) {
        setup();
        const auto t0 = std::chrono::steady_clock::now();
        f();
        t.push_back(seconds(t0));
        total += t.back();
    }
    std::sort(t.begin(), t.end());
    return {t.front(), t[t.size() / 2], int(t.size())};
}

template <class F>
Timing timeRuns(F&& f, int minRuns = 2, int maxRuns = 5, double budget = 1.5) {
    return timeRunsWithSetup([] {}, f, minRuns, maxRuns, budget);
}

// ---- scenes and files --------------------------------------------------------------------------

// The project's stockinette on the drape at `repeats` (the input of the ply, tube and Draco
// measurements), with or without plies.
knit::Scene knitScene(int meshRes, double meshSize, dvec2 repeats, bool plies);
// The scenes of items 2 and 3: the stockinette at its physical size (1 mm yarn radius) on a
// drape of `size` metres, with the library's default plies.
knit::Scene physicalScene(double size);
json sceneSummary(const knit::Scene& s);

std::string workFile(const std::string& work, const std::string& name);
size_t fileBytes(const std::string& path);
// Replaces `path` with `text` atomically (knit::writeFileAtomically).
void writeText(const std::string& path, const std::string& text);

}  // namespace sve
