// The surface level's bake (knit/bake.hpp): one stockinette cell at N pixels across, default
// samples (4 x 4 per pixel, 1 albedo path per hitting sample), 2 plies; the fiber tables and the
// Embree scene are part of every bake.
//
//   cmake --build build --target bake_bench && ./build/bench/bake_bench
#include <benchmark/benchmark.h>

#include "knit/bake.hpp"
#include "knit/generator.hpp"

namespace {

void BM_BakeSurface(benchmark::State& state) {
    const knit::Pattern pattern = knit::generateStockinette();
    knit::BakeOptions o;
    o.width = int(state.range(0));
    size_t pixels = 0;
    for (auto _ : state) {
        const knit::SurfaceBake b = knit::bakeSurface(pattern, o);
        pixels += b.coverage.size();
        benchmark::DoNotOptimize(b.albedo.data());
    }
    state.counters["pixels/s"] = benchmark::Counter(double(pixels), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BakeSurface)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
