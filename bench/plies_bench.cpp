// plies_bench.cpp — throughput of resampling, RMF frames and the full ply sweep (makePlies).
//
// Input: 1000 open knit-like yarns (Crane's plain-knit curve) of 1000 vertices each (1M yarn
// vertices), vertex spacing about twice the resampling spacing (pitch / samplesPerTurn with the
// default pitch of 6 yarn radii and 12 samples per turn), surface normal +z.
// items_per_second = output points per second (ply vertices for makePlies), wall-clock time; the
// CPU column of makePlies is the process's (every thread), for a loaded machine.
// Arguments: makePlies/<plies>/<threads> (threads 0 = TBB default, all cores).
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "knit/frames.hpp"
#include "knit/plies.hpp"
#include "knit/resample.hpp"
#include "util/math.hpp"

namespace {

constexpr double kScale = 0.0005;  // curve scale (metres)
constexpr double kYarnRadius = 0.8 * kScale;

const knit::MappedYarns& benchYarns() {
    static const knit::MappedYarns yarns = [] {
        knit::MappedYarns y;
        const int yarnCount = 1000, vertices = 1000, perLoop = 48;
        std::vector<glm::dvec3> p(vertices);
        for (int k = 0; k < yarnCount; ++k) {
            const double row = 4.5 * kScale * k;
            for (int i = 0; i < vertices; ++i) {
                const double t = knit::util::kTwoPi * i / perLoop;
                p[i] = glm::dvec3(kScale * (t + 1.5 * std::sin(2 * t)), row + kScale * 4.0 * std::cos(t),
                                  kScale * std::cos(2 * t));
            }
            y.curves.addCurve(p.data(), p.size(), false);
        }
        y.normals.assign(y.curves.pointCount(), glm::dvec3(0, 0, 1));
        return y;
    }();
    return yarns;
}

std::unique_ptr<tbb::global_control> threadLimit(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<size_t>(threads));
}

knit::PlyOptions plyOptions(int count) {
    knit::PlyOptions o;
    o.count = count;
    o.yarnRadius = kYarnRadius;
    return o;
}

void BM_MakePlies(benchmark::State& state) {
    const knit::MappedYarns& yarns = benchYarns();
    const auto limit = threadLimit(static_cast<int>(state.range(1)));
    const knit::PlyOptions o = plyOptions(static_cast<int>(state.range(0)));
    size_t plyVertices = 0;
    for (auto _ : state) {
        knit::Plies plies = knit::makePlies(yarns, o);
        plyVertices = plies.curves.pointCount();
        benchmark::DoNotOptimize(plies.curves.points.data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * plyVertices));
    state.counters["yarnVertices"] = static_cast<double>(yarns.curves.pointCount());
    state.counters["plyVertices"] = static_cast<double>(plyVertices);
    // Output bytes per ply vertex (point and radial direction in double), and their rate against
    // memory_bench's triad: makePlies is bound by its arithmetic (frames, sines), not by memory.
    state.counters["bytes_per_vertex"] = 48;
    state.counters["written_bytes_per_second"] = benchmark::Counter(
        static_cast<double>(state.iterations()) * static_cast<double>(plyVertices) * 48.0, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MakePlies)
    ->Args({2, 0})
    ->Args({4, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

void BM_Resample(benchmark::State& state) {
    const knit::MappedYarns& yarns = benchYarns();
    const knit::PlyOptions o = knit::resolvePlyOptions(plyOptions(2));
    knit::ResampleOptions ro;
    ro.spacing = o.pitch / o.samplesPerTurn;
    size_t points = 0;
    for (auto _ : state) {
        knit::MappedYarns r = knit::resampleYarns(yarns, ro);
        points = r.curves.pointCount();
        benchmark::DoNotOptimize(r.curves.points.data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
}
BENCHMARK(BM_Resample)->Unit(benchmark::kMillisecond)->UseRealTime();

// BM_Frames/<precision>: 0 = double, 1 = float32 transport (FrameOptions::precision).
void BM_Frames(benchmark::State& state) {
    knit::FrameOptions fo;
    fo.precision = state.range(0) == 1 ? knit::FramePrecision::Float32 : knit::FramePrecision::Double;
    const knit::PlyOptions o = knit::resolvePlyOptions(plyOptions(2));
    knit::ResampleOptions ro;
    ro.spacing = o.pitch / o.samplesPerTurn;
    const knit::MappedYarns r = knit::resampleYarns(benchYarns(), ro);
    for (auto _ : state) {
        knit::Frames f = knit::rotationMinimizingFrames(r.curves, &r.normals, fo);
        benchmark::DoNotOptimize(f.normal.data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * r.curves.pointCount()));
}
BENCHMARK(BM_Frames)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

}  // namespace

BENCHMARK_MAIN();
