// item_garment.cpp — item 6: garment scale. The whole pipeline to a plies GLB (plies streamed while
// writing) on a 2 m drape: wall and CPU time per stage, peak resident memory; then the same plies
// held in memory for comparison.
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "items.hpp"
#include "knit/base_mesh.hpp"
#include "knit/export.hpp"
#include "knit/generator.hpp"
#include "knit/plies.hpp"
#include "util/platform.hpp"

namespace sve {
namespace {

// The same garment with the plies held in memory (SceneOptions::buildPlies, what the non-glTF
// formats and tubes need): makePlies on the scene's yarns, then the GLB of those plies.
json measureMaterializedGarment(const knit::Scene& streamed, const std::string& path) {
    json out;
    out["reset_peak_ok"] = knit::util::resetPeakResident();
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = cpuSeconds();
    const knit::Plies plies = knit::makePlies(streamed.yarns(), streamed.plyOptions());
    out["plies_seconds"] = seconds(t0);
    knit::ExportInput in;
    in.curves = &plies.curves;
    in.radius = plies.plyRadius;
    knit::ExportOptions eo;
    eo.path = path;
    eo.what = knit::ExportWhat::Plies;
    const auto te = std::chrono::steady_clock::now();
    knit::exportCurves(in, eo);
    out["export_seconds"] = seconds(te);
    out["seconds"] = seconds(t0);
    out["cpu_seconds"] = cpuSeconds() - cpu0;
    out["peak_bytes"] = knit::util::peakResidentBytes();
    out["glb_bytes"] = fileBytes(path);
    fs::remove(path);
    std::fprintf(stderr, "  garment, plies in memory: %.2f s plies + %.2f s GLB, peak %.2f GB\n",
                 out["plies_seconds"].get<double>(), out["export_seconds"].get<double>(),
                 double(out["peak_bytes"].get<size_t>()) / 1e9);
    return out;
}

}  // namespace

json measureGarment(int repeats, const std::string& work) {
    json out;
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = 256;
    mo.size = 2.0;
    const knit::Pattern pattern = knit::generateStockinette();
    knit::BaseMesh mesh = knit::makeDrape(mo);
    knit::SceneOptions so;
    so.placement.repeats = {double(repeats), double(repeats)};
    so.buildPlies = false;  // the GLB export generates and streams the plies (knit/export.hpp)
    // CPU time at every stage boundary (the progress callback runs before each stage): with the
    // wall times of Scene::timings this shows how much of the 2 cores each stage really got.
    std::vector<std::pair<std::string, double>> cpuMarks;
    so.progress = [&](const std::string& stage, int, int) { cpuMarks.emplace_back(stage, cpuSeconds()); };
    const std::string path = workFile(work, "garment.glb");
    fs::remove(path);
    out["reset_peak_ok"] = knit::util::resetPeakResident();
    const size_t rss0 = knit::util::residentBytes();
    const double cpu0 = cpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    const knit::Scene scene = knit::buildScene(pattern, std::move(mesh), so);
    const double cpuBuilt = cpuSeconds();
    const size_t peakBuild = knit::util::peakResidentBytes();
    knit::ExportOptions eo;
    eo.path = path;
    eo.what = knit::ExportWhat::Plies;
    const auto te = std::chrono::steady_clock::now();
    const knit::ExportStats es = knit::exportScene(scene, eo);
    const double exportSeconds = seconds(te);
    const double total = seconds(t0);
    const double cpuTotal = cpuSeconds() - cpu0;
    const size_t peak = knit::util::peakResidentBytes();
    out["repeats"] = repeats;
    out["mesh"] = {{"name", "drape"}, {"res", mo.resU}, {"size_m", mo.size}, {"triangles", scene.mesh().faceCount()}};
    out["cells"] = scene.grid().cells.size();
    out["tiles"] = scene.stages().tiling.tiles.size();
    out["yarn_vertices"] = scene.yarns().curves.pointCount();
    out["tiled_vertices"] = scene.stages().uvYarns.vertexCount();
    out["ply_vertices"] = es.vertices;
    out["yarn_radius_m"] = scene.yarnRadius();
    out["samples_per_turn"] = knit::PlyOptions{}.samplesPerTurn;
    out["plies"] = knit::PlyOptions{}.count;
    for (size_t i = 0; i < scene.timings().size(); ++i) {
        const knit::StageTime& s = scene.timings()[i];
        double cpu = -1;
        if (cpuMarks.size() == scene.timings().size() && cpuMarks[i].first == s.stage)
            cpu = (i + 1 < cpuMarks.size() ? cpuMarks[i + 1].second : cpuBuilt) - cpuMarks[i].second;
        out["stages"].push_back({{"stage", s.stage}, {"seconds", s.seconds}, {"cpu_seconds", cpu}});
    }
    out["stages"].push_back(
        {{"stage", "plies_glb"}, {"seconds", exportSeconds}, {"cpu_seconds", cpuTotal - (cpuBuilt - cpu0)}});
    out["total_seconds"] = total;
    out["cpu_seconds"] = cpuTotal;
    out["glb_bytes"] = fileBytes(path);
    out["export_reported_peak_bytes"] = es.peakMemoryBytes;
    out["rss_before_bytes"] = rss0;
    out["peak_after_build_bytes"] = peakBuild;
    out["peak_bytes"] = peak;
    out["threads"] = std::thread::hardware_concurrency();
    fs::remove(path);
    std::fprintf(
        stderr, "  garment: %zu cells, %zu yarn vertices, %zu ply vertices: %.2f s (CPU %.2f s), peak %.2f GB\n",
        scene.grid().cells.size(), scene.yarns().curves.pointCount(), es.vertices, total, cpuTotal, double(peak) / 1e9);
    out["materialized"] = measureMaterializedGarment(scene, path);
    return out;
}

}  // namespace sve
