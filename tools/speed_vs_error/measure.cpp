// measure.cpp — the `measure` command (see measure.hpp): the machine and the library defaults,
// then each item with the load average before and after it.
#include "measure.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

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

}  // namespace

void measure(const MeasureOptions& o) {
    fs::create_directories(o.work);
    if (fs::path(o.results).has_parent_path()) fs::create_directories(fs::path(o.results).parent_path());
    json r;
    r["meta"] = o.meta;
    r["machine"] = machine();
    r["defaults"] = defaults();
    r["load_start"] = loadJson();
    const auto start = std::chrono::steady_clock::now();
    for (char item : o.items) {
        if (item == ',' || item == ' ') continue;
        std::fprintf(stderr, "speed-vs-error: item %c\n", item);
        const json loadBefore = loadJson();
        const auto t0 = std::chrono::steady_clock::now();
        json j = measureItem(item, o);
        j["load_before"] = loadBefore;
        j["load_after"] = loadJson();
        j["item_seconds"] = seconds(t0);
        r[std::string("item") + item] = j;
        // Written after every item, so a long run keeps what it measured.
        r["measure_seconds"] = seconds(start);
        r["load_end"] = loadJson();
        writeText(o.results, r.dump(1));
    }
}

}  // namespace sve
