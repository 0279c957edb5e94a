// core_bench.cpp — throughput of the core stages at garment-like sizes (>= 1M yarn vertices).
//
// Scene: the project's stockinette (24 vertices per tile) on a drape mesh of 256 x 256 quads
// (131k triangles), repeats 210 x 210 -> ~44k tiles, ~1.06M tiled yarn vertices.
// items_per_second: yarn vertices per second (tiling+stitch, binding, evaluation) or
// triangles per second (grid build). Wall-clock time over all cores (2 here).
#include <benchmark/benchmark.h>

#include "knit/binding.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/scene.hpp"
#include "knit/stitch.hpp"
#include "knit/tiling.hpp"
#include "knit/uv_grid.hpp"
#include "triad.hpp"

namespace {

struct Fixture {
    knit::Scene scene;
    Fixture() {
        knit::ProceduralMeshOptions mo;
        mo.resU = mo.resV = 256;
        knit::SceneOptions o;
        o.placement.repeats = {210, 210};
        o.buildPlies = false;
        scene = knit::buildScene(knit::generateStockinette(), knit::makeDrape(mo), o);
    }
};

const Fixture& fixture() {
    static const Fixture f;
    return f;
}

// Bytes each evaluation streams per yarn vertex (the mesh it gathers from, 131k triangles and
// 66k vertices, ~5 MB, stays in the caches): read face (4), bary (16), height (8); write the
// position and normal in double (24 + 24), or the float32 position (12). The hardware also reads
// each written line first (write allocate): 48 / 12 more. With MeasureProcessCPUTime the CPU
// column is the CPU time of every thread (for a loaded machine: vertices per CPU second).
constexpr double kEvaluateBytes = 4 + 16 + 8 + 24 + 24;  // 76
constexpr double kEvaluateFloatBytes = 4 + 16 + 8 + 12;  // 40
constexpr double kEvaluatePackedBytes = 16 + 12;         // 28: one packed record in, the position out

// Counters: bytes per vertex, the streamed bytes per second and, when BM_TriadAllCores ran before
// in this process (e.g. --benchmark_filter='Triad|BM_Evaluate'), the streamed bytes per CPU
// second as a fraction of the triad's (`of_triad`), both measured under the same load.
void streamedBytes(benchmark::State& state, size_t vertices, double perVertex, double cpuSeconds) {
    const double bytes = double(state.iterations()) * double(vertices) * perVertex;
    state.counters["bytes_per_vertex"] = perVertex;
    state.counters["streamed_bytes_per_second"] = benchmark::Counter(bytes, benchmark::Counter::kIsRate);
    knit::bench::fractionOfTriad(state, bytes, cpuSeconds);
}

// The machine's limit (bench/triad.hpp), registered first so that it runs before the evaluations.
void BM_TriadAllCores(benchmark::State& state) { knit::bench::triadAllCores(state); }
BENCHMARK(BM_TriadAllCores)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

void BM_TilingStitch(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    const knit::PatternAdjacency adj = knit::buildAdjacency(s.pattern());
    size_t vertices = 0;
    for (auto _ : state) {
        const knit::Tiling tiling = knit::tilesForCells(s.pattern(), s.grid().cells);
        const knit::UvYarns yarns = knit::stitchYarns(s.pattern(), adj, tiling, s.placement());
        vertices = yarns.vertexCount();
        benchmark::DoNotOptimize(yarns.uv.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(vertices));
    state.counters["yarn_vertices"] = double(vertices);
}
BENCHMARK(BM_TilingStitch)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GridBuild(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    knit::UvGridOptions o;
    o.cellSize = s.placement().cellSize();
    for (auto _ : state) {
        const knit::UvGrid grid = knit::buildUvGrid(s.mesh(), o);
        benchmark::DoNotOptimize(grid.triangles.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(s.mesh().faceCount()));
    state.counters["cells"] = double(s.grid().cells.size());
}
BENCHMARK(BM_GridBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Binding(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    knit::BindOptions o;
    o.yarnRadius = s.yarnRadius();
    for (auto _ : state) {
        const knit::BindResult r = knit::bindYarns(s.mesh(), s.normals(), s.grid(), s.stages().uvYarns, o);
        benchmark::DoNotOptimize(r.binding.face.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(s.stages().uvYarns.vertexCount()));
    state.counters["yarn_vertices"] = double(s.stages().uvYarns.vertexCount());
}
BENCHMARK(BM_Binding)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Evaluate(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    knit::MappedYarns out;
    const double cpu0 = knit::bench::cpuSeconds();
    for (auto _ : state) {
        knit::evaluateBinding(s.binding(), s.mesh().faces, s.mesh().positions, s.normals(), out);
        benchmark::DoNotOptimize(out.curves.points.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(s.binding().vertexCount()));
    state.counters["yarn_vertices"] = double(s.binding().vertexCount());
    streamedBytes(state, s.binding().vertexCount(), kEvaluateBytes, knit::bench::cpuSeconds() - cpu0);
}
BENCHMARK(BM_Evaluate)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// Per-frame re-posing for a renderer: float32 positions relative to a local origin.
void BM_EvaluateFloat(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    std::vector<glm::vec3> out;
    const double cpu0 = knit::bench::cpuSeconds();
    for (auto _ : state) {
        knit::evaluateBindingFloat(s.binding(), s.mesh().faces, s.mesh().positions, s.normals(), glm::dvec3(0.0), out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(s.binding().vertexCount()));
    streamedBytes(state, s.binding().vertexCount(), kEvaluateFloatBytes, knit::bench::cpuSeconds() - cpu0);
}
BENCHMARK(BM_EvaluateFloat)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// The same from the packed binding (16 bytes per vertex, float32 arithmetic).
void BM_EvaluatePackedFloat(benchmark::State& state) {
    const knit::Scene& s = fixture().scene;
    const knit::PackedBinding packed = knit::packBinding(s.binding());
    std::vector<glm::vec3> out;
    const double cpu0 = knit::bench::cpuSeconds();
    for (auto _ : state) {
        knit::evaluatePackedFloat(packed, s.mesh().faces, s.mesh().positions, s.normals(), glm::dvec3(0.0), out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(s.binding().vertexCount()));
    streamedBytes(state, s.binding().vertexCount(), kEvaluatePackedBytes, knit::bench::cpuSeconds() - cpu0);
}
BENCHMARK(BM_EvaluatePackedFloat)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

}  // namespace

// Partner search of a curves cell (patternFromCurves) over a growing number of short courses: the
// grid search is about linear in the curve ends (the all-pairs search it replaced was quadratic:
// minutes at 40000 courses). tests/hard/search_bounds_test.cpp checks the pairs it finds.
void BM_PartnerSearch(benchmark::State& state) {
    knit::CurveCell cell;
    cell.name = "big.json";
    const int courses = int(state.range(0));
    cell.px = 0.01;
    cell.py = 0.01 * courses;
    cell.radius = 0.001;
    for (int c = 0; c < courses; ++c) {
        const double y = 0.01 * c + 0.005;
        cell.curves.push_back({{0.001, y, 0}, {0.005, y, 0}, {0.009, y, 0}});
    }
    for (auto _ : state) benchmark::DoNotOptimize(knit::patternFromCurves(cell));
    state.SetComplexityN(courses);
}
BENCHMARK(BM_PartnerSearch)->RangeMultiplier(4)->Range(2500, 40000)->Complexity()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
