// memory_bench.cpp — the machine's memory bandwidth, the limit of the per-frame gathers
// (evaluate, plies): a STREAM-style triad (bench/triad.hpp) on every core (TBB, fixed equal
// blocks) and on one. core_bench runs the same triad beside the evaluations.
//
//     cmake --build build --target memory_bench && ./build/bench/memory_bench
#include <benchmark/benchmark.h>

#include "triad.hpp"

namespace {

void BM_TriadAllCores(benchmark::State& state) { knit::bench::triadAllCores(state); }
BENCHMARK(BM_TriadAllCores)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

void BM_TriadOneCore(benchmark::State& state) { knit::bench::triadOneCore(state); }
BENCHMARK(BM_TriadOneCore)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
