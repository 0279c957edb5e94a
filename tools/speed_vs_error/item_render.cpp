// item_render.cpp — item 5: render modes (curves, tubes, grid). A small patch rendered at 1..64
// samples per pixel against a high-sample reference of the same mode; time, RMSE and memory.
// Built only with render_check (KNIT_BUILD_RENDER_CHECK).
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "items.hpp"
#include "knit/base_mesh.hpp"
#include "knit/generator.hpp"
#include "knit/image_io.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/render.hpp"

namespace sve {

json measureRender(const std::string& imageDir) {
    json out;
    // A small patch (6 cm plane, the stockinette at its physical size) in a small image.
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = 8;
    mo.size = 0.06;
    knit::SceneOptions so;
    const knit::Scene scene = knit::buildScene(knit::generateStockinette(), knit::makePlane(mo), so);
    knit::RenderOptions ro;
    ro.width = 80;
    ro.height = 60;
    ro.progress = false;
    ro.light = knit::LightPlacement::Front;
    const int refSpp = 1024;
    out["width"] = ro.width;
    out["height"] = ro.height;
    out["reference_spp"] = refSpp;
    out["light"] = knit::lightPlacementName(ro.light);
    out["tube_sides"] = ro.tubeSides;
    out["scene"] = {{"ply_vertices", scene.plies().curves.pointCount()},
                    {"ply_curves", scene.plies().curves.curveCount()},
                    {"cells", scene.grid().cells.size()},
                    {"plane_m", mo.size}};
    std::map<std::string, knit::Image> refs;
    for (const char* mode : {"curves", "tubes", "grid"}) {
        ro.mode = knit::parseMode(mode);
        ro.spp = refSpp;
        ro.seed = 1000003;
        if (!imageDir.empty()) {
            fs::create_directories(imageDir);
            ro.output = (fs::path(imageDir) / (std::string("render-") + mode + ".png")).string();
        }
        const knit::RenderResult ref = knit::renderScene(scene, ro);
        ro.output.clear();
        refs[mode] = ref.image;
        const double refLum = knit::luminance(ref.image.mean());
        json jm;
        jm["reference_seconds"] = ref.renderSeconds;
        jm["reference_mean_luminance"] = refLum;
        jm["scene_bytes"] = ref.memory.sceneBytes();
        jm["embree_bytes"] = ref.memory.embreeBytes;
        jm["geometry_bytes"] = ref.memory.geometryBytes;
        jm["shading_bytes"] = ref.memory.shadingBytes;
        jm["build_seconds"] = ref.buildSeconds;
        jm["primitives"] = ref.primitives;
        if (!imageDir.empty()) jm["reference_png"] = std::string("render-") + mode + ".png";
        for (int spp : {1, 2, 4, 8, 16, 32, 64}) {
            ro.spp = spp;
            ro.seed = 1;
            const knit::RenderResult r = knit::renderScene(scene, ro);
            const knit::ImageComparison c = knit::compareImages(r.image, ref.image);
            json row;
            row["spp"] = spp;
            row["render_seconds"] = r.renderSeconds;
            row["us_per_sample"] = r.renderSeconds / (double(ro.width) * ro.height * spp) * 1e6;
            row["rays_per_second"] = r.raysPerSecond;
            row["rmse"] = c.rmse;
            row["relative_rmse"] = c.rmse / refLum;
            jm["rows"].push_back(row);
            std::fprintf(stderr, "  %-6s spp %2d: RMSE %.2f%% of mean, %.2f us/sample, scene %.1f MB\n", mode, spp,
                         100 * c.rmse / refLum, row["us_per_sample"].get<double>(), ref.memory.sceneBytes() / 1e6);
        }
        out["modes"][mode] = jm;
    }
    // Differences between the modes' references (geometry, plus the references' own noise).
    // Expected from the references' noise alone: both 1-spp errors scaled to the reference spp.
    auto oneSpp = [&](const char* mode) { return out["modes"][mode]["rows"][0]["relative_rmse"].get<double>(); };
    for (const char* mode : {"tubes", "grid"}) {
        const knit::ImageComparison c = knit::compareImages(refs[mode], refs["curves"]);
        out["modes"][mode]["reference_vs_curves_relative_rmse"] = c.rmse / knit::luminance(refs["curves"].mean());
        out["modes"][mode]["reference_noise_relative_rmse"] =
            std::sqrt((oneSpp(mode) * oneSpp(mode) + oneSpp("curves") * oneSpp("curves")) / refSpp);
    }
    return out;
}

}  // namespace sve
