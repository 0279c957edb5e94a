// bound_scene_bench.cpp — what a farm task saves by loading a bound scene file (`knit bind`)
// instead of binding: the start-up cost of `knit animate` before its first frame, both ways.
//
//   bind: buildScene (stockinette on the built-in drape, as `knit animate` binds its rest pose)
//         and the Animator's bind-time work (resampling layout, rest arc lengths and twist
//         phases, frame seeds);
//   load: readBoundScene of the file `knit bind` would write (from TMPDIR, default /tmp: the page
//         cache, so the disk is not measured) and the Animator adopting what the file stores.
// Sizes: the argument is the repeats per side (50, 150, 350; 350 is the ~3M yarn vertex garment).
// Counters (process CPU seconds, the median of the iterations, so other programs' load does not
// count; construction only, not the destruction): bindCpuSeconds, loadCpuSeconds, loadOverBind,
// fileBytes, yarnVertices, centrePoints; the load's parts: readCpuSeconds (the file read and
// checked; the rest yarns are evaluated lazily, and nothing here asks for them),
// animatorCpuSeconds; and what bounds the load: heldBytes (the resident memory the loaded scene
// and its Animator hold: with format version 5 including the file's pages in its map, which the
// scene's largest arrays are read from in place), allocatedBytes (of it, the anonymous memory:
// what the load allocated and wrote) and touchHeldCpuSeconds (allocating and writing
// allocatedBytes of fresh memory once: the kernel's page faults and zeroing).
//
// boundSceneFrameMappedVsCopied: a frame's CPU time on the mapped scene against the same scene
// copied out of the file (the arrays used in place in the map must not slow the frames).
//
//   build/bench/bound_scene_bench --benchmark_counters_tabular=true
#include "bench_clock.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "knit/animation.hpp"
#include "knit/bound_scene.hpp"
#include "knit/generator.hpp"
#include "util/platform.hpp"

namespace {

using knit::bench::cpuSeconds;
using knit::bench::median;

void boundSceneLoadVsBind(benchmark::State& state) {
    knit::SceneOptions options;
    options.placement.repeats = {double(state.range(0)), double(state.range(0))};
    options.buildPlies = false;
    const knit::Pattern pattern = knit::generateStockinette();
    const knit::BaseMesh drape = knit::makeDrape();
    const char* tmp = std::getenv("TMPDIR");
    const std::string path = std::string(tmp ? tmp : "/tmp") + "/knit_bound_scene_bench.knitbind";
    {
        const knit::Scene rest = buildScene(pattern, drape, options);
        knit::writeBoundScene(path, rest, {});
    }
    std::vector<double> bind, load, read, animator, floor;
    size_t yarnVertices = 0, centres = 0, held = 0, allocated = 0;
    for (auto _ : state) {
        // Construction only: each result is destroyed after its time is taken.
        std::optional<knit::Scene> rest;
        std::optional<knit::Animator> boundAnimator;
        double t0 = cpuSeconds();
        rest.emplace(buildScene(pattern, drape, options));
        boundAnimator.emplace(*rest);
        bind.push_back(cpuSeconds() - t0);
        boundAnimator.reset();
        rest.reset();

        std::optional<knit::BoundScene> loaded;
        std::optional<knit::Animator> loadedAnimator;
        const size_t before = knit::util::residentBytes(), anonymousBefore = knit::util::anonymousResidentBytes();
        t0 = cpuSeconds();
        loaded.emplace(knit::readBoundScene(path));
        const double t1 = cpuSeconds();
        loadedAnimator.emplace(loaded->scene);
        const double t2 = cpuSeconds();
        held = knit::util::residentBytes() - before;
        allocated = knit::util::anonymousResidentBytes() - anonymousBefore;
        read.push_back(t1 - t0);
        animator.push_back(t2 - t1);
        load.push_back(t2 - t0);
        yarnVertices = loaded->scene.binding().vertexCount();  // not yarns(): that evaluates them
        centres = loadedAnimator->plyPointCount() / std::max<size_t>(1, loadedAnimator->plyOptions().count);
        loadedAnimator.reset();
        loaded.reset();

        // The floor: fresh memory of the size the loaded scene and its Animator allocated,
        // allocated and written once (the kernel's page faults and zeroing).
        t0 = cpuSeconds();
        {
            std::vector<char> fresh(allocated, 1);
            benchmark::DoNotOptimize(fresh.data());
            floor.push_back(cpuSeconds() - t0);
        }
    }
    state.counters["bindCpuSeconds"] = median(bind);
    state.counters["loadCpuSeconds"] = median(load);
    state.counters["loadOverBind"] = median(load) / median(bind);
    state.counters["readCpuSeconds"] = median(read);
    state.counters["animatorCpuSeconds"] = median(animator);
    state.counters["heldBytes"] = double(held);
    state.counters["allocatedBytes"] = double(allocated);
    state.counters["touchHeldCpuSeconds"] = median(floor);
    state.counters["fileBytes"] = double(std::filesystem::file_size(path));
    state.counters["yarnVertices"] = double(yarnVertices);
    state.counters["centrePoints"] = double(centres);
    std::filesystem::remove(path);
}
BENCHMARK(boundSceneLoadVsBind)->Arg(50)->Arg(150)->Arg(350)->Iterations(3)->Unit(benchmark::kMillisecond);

// What using the arrays in place in the map costs per frame: an Animator (plies and statistics)
// of the mapped scene (readBoundScene) and of the same scene with every array copied out
// (decodeBoundScene of the bytes, no owner) each evaluate the same frame, alternating.
// Counters: mappedFrameCpuSeconds, copiedFrameCpuSeconds (medians) and their ratio.
void boundSceneFrameMappedVsCopied(benchmark::State& state) {
    knit::SceneOptions options;
    options.placement.repeats = {double(state.range(0)), double(state.range(0))};
    options.buildPlies = false;
    const char* tmp = std::getenv("TMPDIR");
    const std::string path = std::string(tmp ? tmp : "/tmp") + "/knit_bound_scene_frame_bench.knitbind";
    std::vector<glm::dvec3> wave;
    {
        const knit::Scene rest = buildScene(knit::generateStockinette(), knit::makeDrape(), options);
        knit::writeBoundScene(path, rest, {});
        wave = rest.mesh().positions;
        for (glm::dvec3& q : wave) q.z += 0.01 * std::sin(20.0 * q.x);
    }
    const knit::BoundScene mapped = knit::readBoundScene(path);
    std::string bytes(std::filesystem::file_size(path), '\0');
    {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f || std::fread(bytes.data(), 1, bytes.size(), f) != bytes.size()) state.SkipWithError("cannot read");
        if (f) std::fclose(f);
    }
    const knit::BoundScene copied = knit::decodeBoundScene(bytes, path);
    bytes = std::string();
    const knit::Animator onMap(mapped.scene), onCopy(copied.scene);
    knit::AnimationFrame a, b;
    onMap.evaluate(wave, a);  // the buffers allocated, the pages touched once
    onCopy.evaluate(wave, b);
    std::vector<double> mappedSeconds, copiedSeconds;
    for (auto _ : state) {
        double t0 = cpuSeconds();
        onMap.evaluate(wave, a);
        mappedSeconds.push_back(cpuSeconds() - t0);
        t0 = cpuSeconds();
        onCopy.evaluate(wave, b);
        copiedSeconds.push_back(cpuSeconds() - t0);
    }
    if (a.plies.curves.points != b.plies.curves.points) state.SkipWithError("the frames differ");
    state.counters["mappedFrameCpuSeconds"] = median(mappedSeconds);
    state.counters["copiedFrameCpuSeconds"] = median(copiedSeconds);
    state.counters["mappedOverCopied"] = median(mappedSeconds) / median(copiedSeconds);
    std::filesystem::remove(path);
}
BENCHMARK(boundSceneFrameMappedVsCopied)->Arg(350)->Iterations(4)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
