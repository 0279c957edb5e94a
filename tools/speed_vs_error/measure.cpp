// measure.cpp — the `measure` command (see measure.hpp): the machine and the library defaults,
// then each item with the load average before, during (sampled every 5 s) and after it.
#include "measure.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <numeric>
#include <thread>
#include <vector>

#include "items.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/plies.hpp"
#include "knit/sweep.hpp"
#if KNIT_SVE_HAVE_RENDER
#include "knit/render.hpp"
#endif

namespace sve {
namespace {

json machine() {
    return {{"cpu", cpuModel()},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"memory_bytes", memTotalBytes()}};
}

json defaults() {
    json d = {{"samples_per_turn", knit::PlyOptions{}.samplesPerTurn},
              {"plies", knit::PlyOptions{}.count},
              {"tube_options_sides", knit::TubeOptions{}.sides},
              {"tube_options_caps", knit::TubeOptions{}.caps}};
    d["export_sides"] = knit::ExportOptions{}.sides;
    d["draco_bits"] = knit::ExportOptions{}.dracoBits;
#if KNIT_SVE_HAVE_RENDER
    d["render_tube_sides"] = knit::RenderOptions{}.tubeSides;
#endif
    return d;
}

json measureItem(char item, const MeasureOptions& o) {
    switch (item) {
        case '1': return measurePlies();
        case '2': return measureTubeSides(physicalScene(0.2), o.work);
        case '3': return measureDraco(physicalScene(0.1), o.work);
        case '4': return measureBaseMesh();
#if KNIT_SVE_HAVE_RENDER
        case '5': return measureRender(o.images);
        case '7': return measureViews();
#else
        case '5':
        case '7': return {{"skipped", "render_check (knit::render_check) was not built"}};
#endif
        case '6': return measureGarment(o.garmentRepeats, o.work);
        default: throw knit::Error(std::string("unknown item '") + item + "' (expected 1..7)");
    }
}

// Samples the 1-minute load average every 5 s while an item runs (the load before and after it
// miss what other processes did meanwhile): {min, mean, max, samples}.
class LoadSampler {
public:
    LoadSampler()
        : thread_([this] {
              std::unique_lock<std::mutex> lock(mutex_);
              do samples_.push_back(loadAverage()[0]);
              while (!wake_.wait_for(lock, std::chrono::seconds(5), [this] { return stop_; }));
          }) {}
    LoadSampler(const LoadSampler&) = delete;
    LoadSampler& operator=(const LoadSampler&) = delete;
    ~LoadSampler() {
        try {
            stop();
        } catch (...) {  // a destructor must not throw (the item failed already); the samples are lost
        }
    }
    json finish() {
        stop();
        if (samples_.empty()) return json::object();
        const auto [lo, hi] = std::minmax_element(samples_.begin(), samples_.end());
        const double mean = std::accumulate(samples_.begin(), samples_.end(), 0.0) / double(samples_.size());
        return {{"min", *lo}, {"mean", mean}, {"max", *hi}, {"samples", samples_.size()}};
    }

private:
    void stop() {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::vector<double> samples_;
    std::thread thread_;  // last: starts after the members it uses
};

// The results to add to: a new run's header, or (with o.base) the earlier run's results whole.
json startResults(const MeasureOptions& o) {
    if (o.base.empty())
        return {{"meta", o.meta}, {"machine", machine()}, {"defaults", defaults()}, {"load_start", loadJson()}};
    std::ifstream in(o.base);
    if (!in) throw knit::Error("--base: cannot read " + o.base);
    json r = json::parse(in, nullptr, false);
    if (r.is_discarded() || !r.is_object() || !r.contains("meta"))
        throw knit::Error("--base: " + o.base + " is not a speed_vs_error results JSON (no \"meta\")");
    return r;
}

}  // namespace

void measure(const MeasureOptions& o) {
    fs::create_directories(o.work);
    if (fs::path(o.results).has_parent_path()) fs::create_directories(fs::path(o.results).parent_path());
    json r = startResults(o);
    const auto start = std::chrono::steady_clock::now();
    for (char item : o.items) {
        if (item == ',' || item == ' ') continue;
        std::fprintf(stderr, "speed-vs-error: item %c\n", item);
        const json loadBefore = loadJson();
        const auto t0 = std::chrono::steady_clock::now();
        LoadSampler load;
        json j = measureItem(item, o);
        j["load_during"] = load.finish();
        j["load_before"] = loadBefore;
        j["load_after"] = loadJson();
        j["item_seconds"] = seconds(t0);
        j["run"] = o.meta;  // the run that measured this item (differs from the header's after --base)
        r[std::string("item") + item] = j;
        // Written after every item, so a long run keeps what it measured.
        if (o.base.empty()) {
            r["measure_seconds"] = seconds(start);
            r["load_end"] = loadJson();
        }
        writeText(o.results, r.dump(1));
    }
}

}  // namespace sve
