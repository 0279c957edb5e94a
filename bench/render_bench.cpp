// render_check benchmarks: rays/s of each geometry mode (intersection only and full shading) against
// Embree's raw rtcIntersect1 rate on the same ply segments, and the scene memory of each mode.
//   <build>/bench/render_bench --benchmark_counters_tabular=true
// Scenes:
//   * synthetic (BM_Raw*, BM_Mode*): the analytic ply scene (knit/synthetic_scene.hpp): 40 courses
//     x 3 plies over 4 cm, yarn radius 0.5 mm, 16 samples per ply turn, UV cells of 1/16;
//   * pipeline (BM_Pipeline*): the scene `knit render` renders by default (knit::buildScene with
//     default options: stockinette on the drape), rays from its camera position (30-degree view,
//     ~2800 ply radii away) towards random points of the cloth's bounds. Built once (seconds).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <random>

#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <glm/geometric.hpp>

#include "knit/fiber_tables.hpp"
#include "knit/path_tracer.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/scene.hpp"
#include "knit/synthetic_scene.hpp"
#include "tracing/render_image.hpp"
#include "tracing/trace_scene.hpp"
#include "util/math.hpp"

namespace {

using namespace knit;

struct Fixture {
    Scene scene;
    PlyGeometry geometry;
    std::vector<int64_t> cells;
    std::vector<glm::vec3> orgs, dirs;
    glm::dvec3 centre;
    double radius = 0;
};

const Fixture& fixture() {
    static const std::unique_ptr<Fixture> f = [] {
        auto x = std::make_unique<Fixture>();
        SyntheticSceneOptions o;
        o.courses = 40;
        o.size = 0.04;
        o.yarnRadius = 0.0005;
        o.plyCount = 3;
        o.waveAmplitude = 0.0003;
        o.waveLength = 0.004;
        o.cellSize = 1.0 / 16;
        x->scene = makeSyntheticPlyScene(o);
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const glm::dvec3& p : x->scene.plies().curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
        x->centre = 0.5 * (lo + hi);
        x->radius = 0.5 * glm::length(hi - lo);
        x->geometry = buildPlyGeometry(x->scene.plies(), x->centre);
        x->cells = segmentCells(x->scene, x->geometry);
        // Incoherent rays from both sides towards random points of the cloth.
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(-0.02, 0.02);
        for (int i = 0; i < 1 << 16; ++i) {
            const glm::vec3 org = x->geometry.toScene(x->centre + glm::dvec3(u(rng), u(rng), i % 2 ? 0.03 : -0.03));
            const glm::vec3 target = x->geometry.toScene(x->centre + glm::dvec3(u(rng), u(rng), 0.0));
            x->orgs.push_back(org);
            x->dirs.push_back(glm::normalize(target - org));
        }
        return x;
    }();
    return *f;
}

// The default `knit render` scene and camera-like rays (see the file comment).
const Fixture& pipeline() {
    static const std::unique_ptr<Fixture> f = [] {
        auto x = std::make_unique<Fixture>();
        x->scene = buildScene(SceneOptions());
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const glm::dvec3& p : x->scene.plies().curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
        x->centre = 0.5 * (lo + hi);
        x->radius = 0.5 * glm::length(hi - lo);
        x->geometry = buildPlyGeometry(x->scene.plies(), x->centre, PlyMaterial().fiberTwist);
        x->cells = segmentCells(x->scene, x->geometry);
        // The camera of renderScene: on the mean normal (+z for the drape), radius / sin(15 deg) away.
        const glm::dvec3 eye = x->centre + glm::dvec3(0, 0, x->radius / std::sin(15.0 * knit::util::kPi / 180.0));
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(-1, 1);
        for (int i = 0; i < 1 << 16; ++i) {
            const glm::dvec3 target = x->centre + 0.5 * (hi - lo) * glm::dvec3(u(rng), u(rng), u(rng));
            x->orgs.push_back(x->geometry.toScene(eye));
            x->dirs.push_back(glm::normalize(x->geometry.toScene(target) - x->geometry.toScene(eye)));
        }
        return x;
    }();
    return *f;
}

// Embree alone: round linear curves on the same segments, no filter, rtcIntersect1 only.
void rawEmbreeIntersect(benchmark::State& state, const Fixture& f) {
    EmbreeDevice device;
    RTCScene scene = rtcNewScene(device.get());
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, f.geometry.points.data(), 0,
                               sizeof(glm::vec4), f.geometry.points.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, f.geometry.segments.data(), 0,
                               sizeof(uint32_t), f.geometry.segments.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, f.geometry.flags.data(), 0, 1,
                               f.geometry.flags.size());
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    size_t i = 0, hits = 0;
    for (auto _ : state) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        const glm::vec3 o = f.orgs[i & 0xFFFF], d = f.dirs[i & 0xFFFF];
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
        rh.ray.tnear = 0, rh.ray.tfar = 1e30f, rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        ++i;
    }
    state.counters["rays_per_s"] = benchmark::Counter(double(i), benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] = double(hits) / double(i);
    state.counters["scene_MB"] = (device.allocatedBytes() + f.geometry.intersectionBytes()) / 1e6;
    rtcReleaseScene(scene);
}
void BM_RawEmbreeIntersect(benchmark::State& state) { rawEmbreeIntersect(state, fixture()); }
BENCHMARK(BM_RawEmbreeIntersect);
void BM_PipelineRawEmbreeIntersect(benchmark::State& state) { rawEmbreeIntersect(state, pipeline()); }
BENCHMARK(BM_PipelineRawEmbreeIntersect);

TraceSceneOptions options(GeometryMode mode, const Fixture& f) {
    TraceSceneOptions so;
    so.mode = mode;
    so.segmentCells = &f.cells;
    return so;
}

// TraceScene::intersect (entry filter / user callback / tube filter + hit record) on the same rays,
// with the scene memory of the mode and its build time.
void modeIntersect(benchmark::State& state, const Fixture& f) {
    const GeometryMode mode = static_cast<GeometryMode>(state.range(0));
    EmbreeDevice device;
    const auto build0 = std::chrono::steady_clock::now();
    const TraceScene ts(device, f.geometry, options(mode, f));
    const double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - build0).count();
    size_t i = 0, hits = 0;
    for (auto _ : state) {
        TraceHit h;
        hits += ts.intersect(f.orgs[i & 0xFFFF], f.dirs[i & 0xFFFF], 0.f, 1e30f, h);
        ++i;
    }
    state.SetLabel(modeName(mode));
    state.counters["rays_per_s"] = benchmark::Counter(double(i), benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] = double(hits) / double(i);
    state.counters["scene_MB"] = ts.memory().sceneBytes() / 1e6;
    state.counters["embree_MB"] = ts.memory().embreeBytes / 1e6;
    state.counters["geometry_MB"] = ts.memory().geometryBytes / 1e6;
    state.counters["shading_MB"] = ts.memory().shadingBytes / 1e6;
    state.counters["primitives"] = double(ts.primitiveCount());
    state.counters["build_s"] = buildSeconds;
}
void BM_ModeIntersect(benchmark::State& state) { modeIntersect(state, fixture()); }
BENCHMARK(BM_ModeIntersect)->Arg(0)->Arg(1)->Arg(2);
void BM_PipelineModeIntersect(benchmark::State& state) { modeIntersect(state, pipeline()); }
BENCHMARK(BM_PipelineModeIntersect)->Arg(0)->Arg(1)->Arg(2);

// Full path tracing with the ply BSDF, front light: rays/s over every query (camera, shadow and
// continuation rays), on range(1) threads (1 = comparable with the single-thread raw rate).
void modeRender(benchmark::State& state, const Fixture& f, bool farCamera) {
    const GeometryMode mode = static_cast<GeometryMode>(state.range(0));
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(state.range(1)));
    EmbreeDevice device;
    const TraceScene ts(device, f.geometry, options(mode, f));
    const PlyMaterial material;
    const FiberTables tables = buildFiberTables(fiberTableOptions(material, 3));
    TraceSettings s;
    s.width = 96, s.height = 72, s.spp = 4;
    // Synthetic: close up; pipeline: where renderScene puts it (30-degree view of the bounds).
    s.camera.eye =
        f.centre + glm::dvec3(0, 0, farCamera ? f.radius / std::sin(15.0 * knit::util::kPi / 180.0) : 2.5 * f.radius);
    s.camera.fovYDegrees = farCamera ? 30 : s.camera.fovYDegrees;
    s.camera.target = f.centre;
    s.environment = Rgb(0.05);
    s.light.corner = f.centre + glm::dvec3(0.5 * f.radius, 0.5 * f.radius, 2 * f.radius);
    s.light.edgeU = glm::dvec3(0, f.radius, 0);
    s.light.edgeV = glm::dvec3(f.radius, 0, 0);  // cross(U, V) points down to the cloth
    s.light.radiance = Rgb(10.0);
    uint64_t rays = 0;
    double seconds = 0;
    const std::clock_t cpu0 = std::clock();
    for (auto _ : state) {
        TraceStats st;
        benchmark::DoNotOptimize(renderImage(ts, material, tables, s, &st));
        rays += st.rays;
        seconds += st.seconds;
    }
    const double cpuSeconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;  // all threads
    state.SetLabel(modeName(mode));
    state.counters["rays_per_s"] = double(rays) / seconds;
    state.counters["rays_per_cpu_s"] = double(rays) / cpuSeconds;  // per core, load-independent
    state.counters["scene_MB"] = ts.memory().sceneBytes() / 1e6;
}
void BM_ModeRender(benchmark::State& state) { modeRender(state, fixture(), false); }
BENCHMARK(BM_ModeRender)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_PipelineModeRender(benchmark::State& state) { modeRender(state, pipeline(), true); }
BENCHMARK(BM_PipelineModeRender)->ArgsProduct({{0, 1, 2}, {1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
