// mesh_bench.cpp — base-mesh costs: vertex normals (the per-frame part of animation), the UV
// scale, procedural generation, and loading OBJ / binary PLY (OBJ: one pass + weld; PLY: one checking pass + weld).
#include "knit/base_mesh.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace {

knit::BaseMesh drape(int res) {
    knit::ProceduralMeshOptions o;
    o.resU = o.resV = res;
    return knit::makeDrape(o);
}

std::string tempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("knit_mesh_bench_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

// OBJ with v/vt per corner (UVs indexed separately from positions).
std::string writeObj(const knit::BaseMesh& m, const std::string& name) {
    const std::string path = tempPath(name);
    std::ofstream out(path);
    out.precision(17);
    for (const auto& p : m.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& t : m.uvs) out << "vt " << t.x << ' ' << t.y << '\n';
    for (size_t f = 0; f < m.faces.size(); ++f) {
        out << 'f';
        for (int k = 0; k < 3; ++k) out << ' ' << m.faces[f][k] + 1 << '/' << m.faceUvs[f][k] + 1;
        out << '\n';
    }
    return path;
}

// Binary PLY with per-vertex u,v: one PLY vertex per UV vertex (seams duplicated, then welded).
std::string writePly(const knit::BaseMesh& m, const std::string& name) {
    std::vector<glm::dvec3> pos(m.uvs.size());
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) pos[m.faceUvs[f][k]] = m.positions[m.faces[f][k]];
    const std::string path = tempPath(name);
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.uvs.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n"
        << "element face " << m.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (size_t i = 0; i < m.uvs.size(); ++i) {
        const float v[5] = {float(pos[i].x), float(pos[i].y), float(pos[i].z), float(m.uvs[i].x), float(m.uvs[i].y)};
        out.write(reinterpret_cast<const char*>(v), sizeof(v));
    }
    for (const auto& f : m.faceUvs) {
        const unsigned char n = 3;
        const int32_t idx[3] = {int32_t(f.x), int32_t(f.y), int32_t(f.z)};
        out.write(reinterpret_cast<const char*>(&n), 1);
        out.write(reinterpret_cast<const char*>(idx), sizeof(idx));
    }
    return path;
}

void BM_VertexNormals(benchmark::State& state) {
    const knit::BaseMesh m = drape(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(knit::vertexNormals(m.positions, m.faces));
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(m.faces.size()));
}
BENCHMARK(BM_VertexNormals)->Arg(64)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_UvToMetreScale(benchmark::State& state) {
    const knit::BaseMesh m = drape(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(knit::uvToMetreScale(m));
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(m.faces.size()));
}
BENCHMARK(BM_UvToMetreScale)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_MakeDrape(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(drape(int(state.range(0))));
}
BENCHMARK(BM_MakeDrape)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_LoadObj(benchmark::State& state) {
    knit::ProceduralMeshOptions o;
    o.resU = o.resV = int(state.range(0));
    const std::string path = writeObj(knit::makeCylinder(o), "cyl.obj");
    size_t faces = 0;
    for (auto _ : state) faces = knit::loadMesh(path).faces.size();
    std::filesystem::remove(path);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(faces));
}
BENCHMARK(BM_LoadObj)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

void BM_LoadBinaryPlyWithWeld(benchmark::State& state) {
    knit::ProceduralMeshOptions o;
    o.resU = o.resV = int(state.range(0));
    const std::string path = writePly(knit::makeCylinder(o), "cyl.ply");
    size_t faces = 0;
    for (auto _ : state) faces = knit::loadMesh(path).faces.size();
    std::filesystem::remove(path);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(faces));
}
BENCHMARK(BM_LoadBinaryPlyWithWeld)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
