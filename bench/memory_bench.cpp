// memory_bench.cpp — the machine's memory bandwidth, the limit of the per-frame gathers
// (evaluate, plies): a STREAM-style triad a[i] = b[i] + s c[i] over three arrays of doubles far
// larger than the caches, on every core (TBB, fixed equal blocks) and on one.
//
// bytes_per_second counts what STREAM counts: 24 bytes per element (two read, one written). The
// hardware moves 32 (the written line is read first unless stores stream past the cache), which
// the counter `bytes_with_write_allocate` gives. Arrays: KNIT_TRIAD_MB megabytes each (default
// 256, three arrays: 768 MB; STREAM asks for at least 4x the last-level cache).
//
//     cmake --build build --target memory_bench && ./build/bench/memory_bench
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace {

size_t elements() {
    const char* mb = std::getenv("KNIT_TRIAD_MB");
    const size_t bytes = size_t(mb ? std::atof(mb) : 256.0) * 1024 * 1024;
    return bytes / sizeof(double);
}

struct Arrays {
    std::vector<double> a, b, c;
    Arrays() : a(elements(), 0.0), b(elements(), 1.0), c(elements(), 2.0) {}
};

Arrays& arrays() {
    static Arrays x;
    return x;
}

void triad(double* a, const double* b, const double* c, double s, size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) a[i] = b[i] + s * c[i];
}

void report(benchmark::State& state, size_t n) {
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(24 * n));
    state.counters["bytes_with_write_allocate"] =
        benchmark::Counter(double(state.iterations()) * 32.0 * double(n), benchmark::Counter::kIsRate);
    state.counters["array_MB"] = double(n * sizeof(double)) / (1024.0 * 1024.0);
}

// Every core: fixed equal blocks (one per 1M elements), so the threads stream separate ranges.
void BM_TriadAllCores(benchmark::State& state) {
    Arrays& x = arrays();
    const size_t n = x.a.size();
    const double s = 3.0;
    tbb::static_partitioner part;
    for (auto _ : state) {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, n, size_t(1) << 20),
            [&](const tbb::blocked_range<size_t>& r) {
                triad(x.a.data(), x.b.data(), x.c.data(), s, r.begin(), r.end());
            },
            part);
        benchmark::DoNotOptimize(x.a.data());
        benchmark::ClobberMemory();
    }
    report(state, n);
}
BENCHMARK(BM_TriadAllCores)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

void BM_TriadOneCore(benchmark::State& state) {
    Arrays& x = arrays();
    const size_t n = x.a.size();
    for (auto _ : state) {
        triad(x.a.data(), x.b.data(), x.c.data(), 3.0, 0, n);
        benchmark::DoNotOptimize(x.a.data());
        benchmark::ClobberMemory();
    }
    report(state, n);
}
BENCHMARK(BM_TriadOneCore)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
