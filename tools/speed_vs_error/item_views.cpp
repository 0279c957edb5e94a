// item_views.cpp — item 7: level of detail for a view (knit/detail.hpp) against `--detail full`.
// The garment of issue 11 (the drape at 256 x 256 quads, the stockinette 660 x 660) rendered
// front-lit at 320 x 240, 32 samples per pixel, from four cameras: far (the default framing),
// mid (a grazing view ~6.7 cm from the cloth), close (eye ~2.8 cm from the top of the drape) and
// 1cm (eye 1 cm from it, along the close camera's line of sight). Per camera: `--detail view`
// renders with the level thresholds scaled by 0.5, 1 (the default) and 2 (a cell keeps a finer
// level down to half / twice the projected size), plus the default at a second seed, all run
// before the full scene is built so that each view's peak memory (reset before it) is its own,
// not what the allocator kept from the ~10 GB full scene; then one full-detail reference render
// per camera and the full render at a second seed (the noise floor of the comparison: how close
// another full render comes). Each gives the geometry kept (curve segments traced, surface
// triangles), wall time of scene + render, peak memory, the camera's distance to its target, and
// the image error against the reference: mean radiance per channel and the RMSE of 4 x 4 block
// mean luminances, both relative to the reference's mean.
// Built only with render_check (KNIT_BUILD_RENDER_CHECK).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif

#include <glm/geometric.hpp>

#include "items.hpp"
#include "knit/base_mesh.hpp"
#include "knit/generator.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/render.hpp"
#include "util/platform.hpp"

namespace sve {
namespace {

struct Camera {
    const char* name;
    bool framed;  // the default camera (no eye)
    knit::View view;
};

using knit::luminance;

// Mean radiance per channel of `image` relative to `reference` (-0.05 = 5% darker), and the RMSE
// of the two images' 4 x 4 block mean luminances over the reference's mean luminance.
json imageError(const knit::Image& image, const knit::Image& reference) {
    const knit::Rgb a = image.mean(), b = reference.mean();
    const double mean = luminance(b);
    double sum = 0;
    int blocks = 0;
    for (int by = 0; by + 4 <= reference.height; by += 4)
        for (int bx = 0; bx + 4 <= reference.width; bx += 4) {
            double da = 0, db = 0;
            for (int y = by; y < by + 4; ++y)
                for (int x = bx; x < bx + 4; ++x)
                    da += luminance(image.pixel(x, y)), db += luminance(reference.pixel(x, y));
            const double d = (da - db) / 16.0;
            sum += d * d;
            ++blocks;
        }
    return {{"mean_relative", {a.r / b.r - 1, a.g / b.g - 1, a.b / b.b - 1}},
            {"block_rmse_relative", std::sqrt(sum / std::max(blocks, 1)) / mean}};
}

knit::RenderOptions renderOptions(const Camera& c, uint64_t seed) {
    knit::RenderOptions ro;
    ro.width = 320;
    ro.height = 240;
    ro.spp = 32;
    ro.seed = seed;
    ro.progress = false;
    ro.light = knit::LightPlacement::Front;
    if (!c.framed) ro.view = c.view;
    ro.budget = knit::MemoryBudget(uint64_t(14) << 30);  // the full render needs ~10 GB (issue 11)
    return ro;
}

knit::SceneOptions garmentScene() {
    knit::SceneOptions so;
    so.placement.repeats = {660.0, 660.0};
    so.budget = knit::MemoryBudget(uint64_t(14) << 30);
    return so;
}

// One `--detail view` render of camera c with thresholds scaled by `scale`; its image is compared
// with the full render's later (the full scene is built after every view, so the view's peak is its own).
struct ViewRun {
    json stats;
    knit::Image image;
};

ViewRun viewRender(const knit::Pattern& pattern, const knit::BaseMesh& mesh, const Camera& c, double scale,
                   uint64_t seed) {
    // Freed memory the allocator kept from the previous view (e.g. the mid view's 1M segments)
    // goes back to the system first, or it would count in this view's peak.
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
    const size_t residentBefore = knit::util::residentBytes();
    knit::util::resetPeakResident();
    const auto t0 = std::chrono::steady_clock::now();
    knit::SceneOptions so = garmentScene();
    knit::DetailOptions d;
    if (!c.framed) d.view = c.view;
    d.viewSettings.width = 320, d.viewSettings.height = 240;
    const knit::DetailOptions defaults;
    d.plyPixels = {scale * defaults.plyPixels.enter, scale * defaults.plyPixels.leave};
    d.yarnPixels = {scale * defaults.yarnPixels.enter, scale * defaults.yarnPixels.leave};
    so.detail = d;
    const knit::Scene scene = knit::buildScene(pattern, mesh, so);
    knit::RenderResult r = knit::renderScene(scene, renderOptions(c, seed));
    json out = {{"threshold_scale", scale},
                {"seed", seed},
                {"seconds", seconds(t0)},
                {"peak_bytes", knit::util::peakResidentBytes()},
                {"resident_before_bytes", residentBefore},
                {"segments", r.segments},
                {"surface_triangles", r.surfaceTriangles}};
    std::fprintf(stderr, "  %s view x%.2g seed %llu: %.1f s, %.0f MiB peak, %zu segments, %zu surface triangles\n",
                 c.name, scale, static_cast<unsigned long long>(seed), out["seconds"].get<double>(),
                 out["peak_bytes"].get<double>() / (1 << 20), r.segments, r.surfaceTriangles);
    return {out, std::move(r.image)};
}

// The view run's error against the full render of its camera.
void compareView(json& view, const knit::Image& image, const knit::Image& reference, const char* camera,
                 size_t fullSegments) {
    view.update(imageError(image, reference));
    view["segments_fraction"] = view["segments"].get<double>() / double(fullSegments);
    std::fprintf(stderr, "  %s view x%.2g seed %d: %.3g%% of full, mean %+.1f%% %+.1f%% %+.1f%%, block RMSE %.1f%%\n",
                 camera, view["threshold_scale"].get<double>(), view["seed"].get<int>(),
                 100.0 * view["segments_fraction"].get<double>(), 100 * view["mean_relative"][0].get<double>(),
                 100 * view["mean_relative"][1].get<double>(), 100 * view["mean_relative"][2].get<double>(),
                 100 * view["block_rmse_relative"].get<double>());
}

}  // namespace

json measureViews() {
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = 256;
    const knit::BaseMesh mesh = knit::makeDrape(mo);
    const knit::Pattern pattern = knit::generateStockinette();
    const glm::dvec3 top(0, 0.1667, 0);  // the top of the drape
    std::vector<Camera> cameras{{"far", true, {}},
                                {"mid", false, {{0.04, 0.22, 0.0}, top, {0, 0, -1}, 30, 320, 240}},
                                {"close", false, {{0.015, 0.19, 0.0}, top, {0, 0, -1}, 30, 320, 240}},
                                {"1cm", false, {{0.00541, 0.17511, 0.0}, top, {0, 0, -1}, 30, 320, 240}}};
    // Step 1: the view renders, before the full scene exists: each view's peak resident memory is its
    // own plus what the process holds then (mesh, pattern, the earlier views' images: a few MB).
    json out;
    std::vector<std::vector<ViewRun>> views(cameras.size());
    for (size_t k = 0; k < cameras.size(); ++k) {
        for (const double scale : {0.5, 1.0, 2.0}) views[k].push_back(viewRender(pattern, mesh, cameras[k], scale, 1));
        views[k].push_back(viewRender(pattern, mesh, cameras[k], 1.0, 2));
    }
    // Step 2: the full-detail references (one scene with every ply, rendered from each camera).
    std::vector<knit::Image> references;
    size_t fullSegments = 0;
    {
        knit::util::resetPeakResident();
        const auto t0 = std::chrono::steady_clock::now();
        const knit::Scene full = knit::buildScene(pattern, mesh, garmentScene());
        out["full_scene_seconds"] = seconds(t0);
        for (const Camera& c : cameras) {
            const auto tr = std::chrono::steady_clock::now();
            const knit::RenderResult r = knit::renderScene(full, renderOptions(c, 1));
            references.push_back(r.image);
            fullSegments = r.segments;
            const knit::Rgb m = r.image.mean();
            out[c.name]["full"] = {{"render_seconds", seconds(tr)},
                                   {"segments", r.segments},
                                   {"mean", {m.r, m.g, m.b}},
                                   {"eye", {r.view.eye.x, r.view.eye.y, r.view.eye.z}},
                                   {"target", {r.view.target.x, r.view.target.y, r.view.target.z}}};
            out[c.name]["distance_m"] = glm::length(r.view.eye - r.view.target);
            std::fprintf(stderr, "  %s full: %.1f s render, %zu segments\n", c.name, seconds(tr), r.segments);
            // The noise floor: the same full render at another seed against the reference.
            const json noise = imageError(knit::renderScene(full, renderOptions(c, 2)).image, r.image);
            out[c.name]["full"]["seed2"] = noise;
            std::fprintf(stderr, "  %s full seed 2: block RMSE %.1f%%\n", c.name,
                         100 * noise["block_rmse_relative"].get<double>());
        }
        out["full_peak_bytes"] = knit::util::peakResidentBytes();
    }
    // Step 3: the views' errors against the references.
    out["views_before_full"] = true;
    for (size_t k = 0; k < cameras.size(); ++k) {
        json& runs = out[cameras[k].name]["view"] = json::array();
        for (ViewRun& v : views[k]) {
            compareView(v.stats, v.image, references[k], cameras[k].name, fullSegments);
            runs.push_back(std::move(v.stats));
        }
    }
    return out;
}

}  // namespace sve
