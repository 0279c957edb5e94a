// export_bench.cpp — tube sweep speed, GLB / curve writing speed, Draco speed / ratio / error,
// and the peak memory of a streamed 10M-ply-vertex export.
//
// Run:  <build>/bench/export_bench --benchmark_counters_tabular=true
//       (files go to the system temp folder and are removed after each benchmark)
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <chrono>
#include <unordered_map>

#include <glm/geometric.hpp>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "knit/export.hpp"
#include "knit/sweep.hpp"
#include "util/math.hpp"
#include "util/platform.hpp"

namespace {

using namespace knit;

// Ply-like curves: `curves` two-turn-per-cm helices of `points` points around wavy rows.
Polylines plyCurves(int curves, int points, double plyRadius = 0.0004) {
    Polylines c;
    std::vector<glm::dvec3> p(static_cast<size_t>(points));
    for (int k = 0; k < curves; ++k) {
        const double row = 0.004 * (k / 2), phase = util::kPi * (k % 2);
        for (int i = 0; i < points; ++i) {
            const double s = 0.0005 * i;  // 0.5 mm spacing
            const double th = util::kTwoPi * s / 0.006 + phase;
            p[size_t(i)] = glm::dvec3(s, row + 0.001 * std::sin(s / 0.003) + 2.5 * plyRadius * std::cos(th),
                                      0.0008 * std::cos(s / 0.002) + 2.5 * plyRadius * std::sin(th));
        }
        c.addCurve(p.data(), p.size(), false);
    }
    return c;
}

std::string tempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("knit_export_bench_" + name)).string();
}

void removeOutputs(const std::string& path) {
    std::error_code ec;
    std::filesystem::remove(path, ec);
    const std::filesystem::path p(path);
    for (int k = 0; k < 64; ++k) {
        const auto bin = p.parent_path() / (p.stem().string() + (k == 0 ? ".bin" : "_" + std::to_string(k) + ".bin"));
        std::filesystem::remove(bin, ec);
    }
}

// Tube generation: vertices per second (sides = 8, i.e. 9 vertices per ring with the seam).
void BM_SweepTubes(benchmark::State& state) {
    const Polylines c = plyCurves(400, int(state.range(0)));
    TubeOptions o;
    o.sides = 8;
    size_t vertices = 0;
    for (auto _ : state) {
        TubeMesh m = sweepTubes(c, 0.0004, o, 0, c.curveCount(), glm::dvec3(0.1, 0.2, 0.0));
        vertices = m.vertexCount();
        benchmark::DoNotOptimize(m.positions.data());
    }
    state.counters["vertices"] = double(vertices);
    state.counters["vertices/s"] =
        benchmark::Counter(double(vertices) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SweepTubes)->Arg(2500)->Unit(benchmark::kMillisecond)->UseRealTime();

// The streaming export's sweep: chunks of ~1M tube vertices swept into one reused mesh (the
// memory is page-faulted once), i.e. the sweep cost inside exportScene for tubes.
void BM_SweepTubesChunked(benchmark::State& state) {
    const Polylines c = plyCurves(400, 2500);
    TubeOptions o;
    o.sides = 8;
    const size_t perChunk = size_t(state.range(0));
    const size_t curvesPerChunk = std::max<size_t>(1, perChunk / tubeVertexCount(2500, false, o));
    TubeMesh m;
    size_t vertices = 0;
    for (auto _ : state) {
        vertices = 0;
        for (size_t first = 0; first < c.curveCount(); first += curvesPerChunk) {
            sweepTubes(c, 0.0004, o, first, std::min(c.curveCount(), first + curvesPerChunk), glm::dvec3(0.1, 0.2, 0.0),
                       m);
            vertices += m.vertexCount();
            benchmark::DoNotOptimize(m.positions.data());
        }
    }
    state.counters["vertices"] = double(vertices);
    state.counters["vertices/s"] =
        benchmark::Counter(double(vertices) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SweepTubesChunked)->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();

// Exports `c` to a fresh file (outside the timing) in every iteration; reports MB and MB/s.
ExportStats timeExports(benchmark::State& state, const Polylines& c, const ExportOptions& o) {
    ExportInput in;
    in.curves = &c;
    in.radius = 0.0004;
    ExportStats s;
    for (auto _ : state) {
        state.PauseTiming();
        removeOutputs(o.path);  // a fresh file each time (no replace-by-rename writeback)
        state.ResumeTiming();
        s = exportCurves(in, o);
    }
    removeOutputs(o.path);
    state.counters["MB"] = double(s.bytes) / 1e6;
    state.counters["MB/s"] =
        benchmark::Counter(double(s.bytes) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
    return s;
}

// GLB export end to end (sweep + write), tube meshes: bytes written per second.
void BM_ExportGlbTubes(benchmark::State& state) {
    const Polylines c = plyCurves(400, 2500);
    ExportOptions o;
    o.path = tempPath("tubes.glb");
    o.what = ExportWhat::Tubes;
    o.quantize = state.range(0) == 1;
    const ExportStats s = timeExports(state, c, o);
    state.counters["vertices"] = double(s.vertices);
    state.SetLabel(o.quantize ? "KHR_mesh_quantization" : "float32");
}
BENCHMARK(BM_ExportGlbTubes)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// GLB curves (one non-indexed LINE_STRIP per curve): bytes written per second.
void BM_ExportGlbCurves(benchmark::State& state) {
    const Polylines c = plyCurves(4000, 2500);
    ExportOptions o;
    o.path = tempPath("curves.glb");
    o.what = ExportWhat::Plies;
    timeExports(state, c, o);
}
BENCHMARK(BM_ExportGlbCurves)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// Draco on one tube chunk (the size --draco uses by default): encode / decode speed, compression ratio against the plain GLB
// attribute + index bytes, and the max position error (decoded vs. nearest original vertex of
// the same ring) in metres and in ply radii.
std::unique_ptr<draco::Mesh> toDraco(const TubeMesh& m) {
    auto meshPtr = std::make_unique<draco::Mesh>();
    draco::Mesh& mesh = *meshPtr;
    const uint32_t n = uint32_t(m.vertexCount());
    mesh.set_num_points(n);
    mesh.SetNumFaces(m.triangles.size());
    for (size_t f = 0; f < m.triangles.size(); ++f)
        mesh.SetFace(draco::FaceIndex(uint32_t(f)),
                     {draco::PointIndex(m.triangles[f].x), draco::PointIndex(m.triangles[f].y),
                      draco::PointIndex(m.triangles[f].z)});
    auto add = [&](draco::GeometryAttribute::Type t, int comps, const void* data) {
        draco::GeometryAttribute ga;
        ga.Init(t, nullptr, uint8_t(comps), draco::DT_FLOAT32, false, 4 * comps, 0);
        const int id = mesh.AddAttribute(ga, true, n);
        mesh.attribute(id)->buffer()->Write(0, data, size_t(4 * comps) * n);
    };
    add(draco::GeometryAttribute::POSITION, 3, m.positions.data());
    add(draco::GeometryAttribute::NORMAL, 3, m.normals.data());
    add(draco::GeometryAttribute::TEX_COORD, 2, m.uvs.data());
    add(draco::GeometryAttribute::GENERIC, 4, m.tangents.data());
    return meshPtr;
}

void BM_Draco(benchmark::State& state) {
    const int bits = int(state.range(0));
    const double radius = 0.0004;
    const Polylines c = plyCurves(100, 290, radius);  // ~270k tube vertices: one auto-sized Draco chunk
    TubeOptions to;
    to.sides = 8;
    const TubeMesh tube = sweepTubes(c, radius, to, 0, c.curveCount(), glm::dvec3(0.3, 0.1, 0.0));
    const std::unique_ptr<draco::Mesh> mesh = toDraco(tube);
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    enc.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, 10);
    enc.SetSpeedOptions(3, 3);  // = --draco-level 7 (the default)
    enc.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buffer;
    double encodeSeconds = 0, decodeSeconds = 0;
    std::unique_ptr<draco::Mesh> decoded;
    for (auto _ : state) {
        buffer.Clear();
        auto t0 = std::chrono::steady_clock::now();
        if (!enc.EncodeMeshToBuffer(*mesh, &buffer).ok()) state.SkipWithError("encode failed");
        auto t1 = std::chrono::steady_clock::now();
        draco::DecoderBuffer in;
        in.Init(buffer.data(), buffer.size());
        draco::Decoder dec;
        auto r = dec.DecodeMeshFromBuffer(&in);
        auto t2 = std::chrono::steady_clock::now();
        if (!r.ok()) state.SkipWithError("decode failed");
        decoded = std::move(r).value();
        encodeSeconds += std::chrono::duration<double>(t1 - t0).count();
        decodeSeconds += std::chrono::duration<double>(t2 - t1).count();
    }
    // Max position error: each decoded point against the nearest original vertex (grid search).
    const double cell = radius;
    std::unordered_map<int64_t, std::vector<uint32_t>> grid;
    auto key = [&](const glm::vec3& p, int dx, int dy, int dz) {
        const int64_t x = int64_t(std::floor(p.x / cell)) + dx, y = int64_t(std::floor(p.y / cell)) + dy,
                      z = int64_t(std::floor(p.z / cell)) + dz;
        return (x * 73856093) ^ (y * 19349663) ^ (z * 83492791);
    };
    for (uint32_t i = 0; i < tube.vertexCount(); ++i) grid[key(tube.positions[i], 0, 0, 0)].push_back(i);
    const draco::PointAttribute* pa = decoded->GetNamedAttribute(draco::GeometryAttribute::POSITION);
    double maxErr = 0;
    for (uint32_t i = 0; i < decoded->num_points(); ++i) {
        glm::vec3 p;
        pa->GetMappedValue(draco::PointIndex(i), &p[0]);
        double best = 1e30;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find(key(p, dx, dy, dz));
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) best = std::min(best, double(glm::length(p - tube.positions[j])));
                }
        maxErr = std::max(maxErr, best);
    }
    const double plain = double(tube.vertexCount()) * 48.0 + double(tube.triangles.size()) * 12.0;
    const double it = double(state.iterations());
    state.counters["vertices"] = double(tube.vertexCount());
    state.counters["encode_Mvert/s"] = double(tube.vertexCount()) * it / encodeSeconds / 1e6;
    state.counters["decode_Mvert/s"] = double(tube.vertexCount()) * it / decodeSeconds / 1e6;
    state.counters["ratio_vs_glb"] = plain / double(buffer.size());
    state.counters["maxErr_um"] = maxErr * 1e6;
    state.counters["maxErr_radii"] = maxErr / radius;
}
BENCHMARK(BM_Draco)->Arg(11)->Arg(14)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// Streaming: 10M ply vertices exported as GLB tubes; peak resident memory growth during the
// export (VmHWM reset through /proc/self/clear_refs) against the size of the whole tube mesh.
// Run it alone (--benchmark_filter=Streaming): memory kept by earlier benchmarks hides growth.
void BM_StreamingPeakMemory(benchmark::State& state) {
    const Polylines c = plyCurves(4000, 2500);  // 10M ply points
    ExportInput in;
    in.curves = &c;
    in.radius = 0.0004;
    ExportOptions o;
    o.path = tempPath("stream.glb");
    o.what = ExportWhat::Tubes;
    o.chunkVertices = size_t(1) << 20;
    ExportStats s;
    size_t base = 0;
    for (auto _ : state) {
        util::resetPeakResident();  // VmHWM back to the current RSS
        base = util::peakResidentBytes();
        s = exportCurves(in, o);
    }
    removeOutputs(o.path);
    const double wholeMesh = double(s.vertices) * (48 + 4) + double(s.triangles) * 12;
    state.counters["plyVertices"] = double(c.pointCount());
    state.counters["tubeVertices"] = double(s.vertices);
    state.counters["GB_written"] = double(s.bytes) / 1e9;
    state.counters["buffers"] = double(s.buffers);
    state.counters["rssBefore_MB"] = double(base) / 1e6;
    state.counters["peak_MB"] = double(s.peakMemoryBytes) / 1e6;
    state.counters["peakGrowth_MB"] = (double(s.peakMemoryBytes) - double(base)) / 1e6;
    state.counters["wholeMesh_MB"] = wholeMesh / 1e6;
    state.counters["MB/s"] = double(s.bytes) / s.seconds / 1e6;
}
BENCHMARK(BM_StreamingPeakMemory)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
