// triad.hpp — the machine's memory limit as a STREAM-style triad a[i] = b[i] + s c[i] over three
// arrays of doubles far larger than the caches, shared by memory_bench (the limit alone) and
// core_bench (the limit and the evaluations in one process, so that the load other programs put
// on the shared machine weighs on both alike).
//
// bytes_per_second counts what STREAM counts: 24 bytes per element (two read, one written). The
// hardware moves 32 (the written line is read first unless stores stream past the cache), which
// the counter `bytes_with_write_allocate` gives. Arrays: KNIT_TRIAD_MB megabytes each (default
// 256, three arrays: 768 MB; STREAM asks for at least 4x the last-level cache).
//
// Every all-cores run records its streamed bytes per second of process CPU time (all threads,
// cpuSeconds); a benchmark run after it in the same process reports its own bytes per CPU second
// as a fraction of their median (counter `of_triad`, see fractionOfTriad).
#pragma once
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "bench_clock.hpp"

namespace knit::bench {

inline size_t triadElements() {
    const char* mb = std::getenv("KNIT_TRIAD_MB");
    const size_t bytes = size_t(mb ? std::atof(mb) : 256.0) * 1024 * 1024;
    return bytes / sizeof(double);
}

struct TriadArrays {
    std::vector<double> a, b, c;
    TriadArrays() : a(triadElements(), 0.0), b(triadElements(), 1.0), c(triadElements(), 2.0) {}
};

// Allocated by the first triad run only (a process that runs no triad does not pay 768 MB).
inline TriadArrays& triadArrays() {
    static TriadArrays x;
    return x;
}

inline void triad(double* a, const double* b, const double* c, double s, size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) a[i] = b[i] + s * c[i];
}

// Streamed bytes per CPU second of the all-cores triad runs so far in this process, with their
// iteration counts (the library's runs that size the iteration count come first, with fewer).
struct TriadRun {
    int64_t iterations;
    double bytesPerCpuSecond;
};
inline std::vector<TriadRun>& triadRuns() {
    static std::vector<TriadRun> runs;
    return runs;
}

// Counters `of_triad` (this run's streamed bytes per CPU second over the median triad run's of
// this process) and `triad_bytes_per_cpu_second`; nothing when no triad ran before.
inline void fractionOfTriad(benchmark::State& state, double streamedBytes, double cpuSpent) {
    int64_t most = 0;
    for (const TriadRun& t : triadRuns()) most = std::max(most, t.iterations);
    std::vector<double> r;  // the measured runs only: those of the most iterations
    for (const TriadRun& t : triadRuns())
        if (t.iterations == most) r.push_back(t.bytesPerCpuSecond);
    if (r.empty() || cpuSpent <= 0.0) return;
    const double limit = median(r);
    state.counters["triad_bytes_per_cpu_second"] = limit;
    state.counters["of_triad"] = streamedBytes / cpuSpent / limit;
}

inline void reportTriad(benchmark::State& state, size_t n) {
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(24 * n));
    state.counters["bytes_with_write_allocate"] =
        benchmark::Counter(double(state.iterations()) * 32.0 * double(n), benchmark::Counter::kIsRate);
    state.counters["array_MB"] = double(n * sizeof(double)) / (1024.0 * 1024.0);
}

// Every core: fixed equal blocks (one per 1M elements), so the threads stream separate ranges.
inline void triadAllCores(benchmark::State& state) {
    TriadArrays& x = triadArrays();
    const size_t n = x.a.size();
    const double s = 3.0;
    tbb::static_partitioner part;
    const double cpu0 = cpuSeconds();
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
    const double cpu = cpuSeconds() - cpu0;
    if (cpu > 0.0) {
        const double rate = double(state.iterations()) * 24.0 * double(n) / cpu;
        triadRuns().push_back({int64_t(state.iterations()), rate});
        state.counters["bytes_per_cpu_second"] = rate;
    }
    reportTriad(state, n);
}

inline void triadOneCore(benchmark::State& state) {
    TriadArrays& x = triadArrays();
    const size_t n = x.a.size();
    for (auto _ : state) {
        triad(x.a.data(), x.b.data(), x.c.data(), 3.0, 0, n);
        benchmark::DoNotOptimize(x.a.data());
        benchmark::ClobberMemory();
    }
    reportTriad(state, n);
}

}  // namespace knit::bench
