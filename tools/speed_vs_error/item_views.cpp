// item_views.cpp — item 7: level of detail for a view (knit/detail.hpp) against `--detail full`.
// The garment of issue 11 (the drape at 256 x 256 quads, the stockinette 660 x 660) rendered
// front-lit at 320 x 240, 32 samples per pixel, from four cameras: far (the default framing),
// mid (a grazing view ~6 cm from the cloth), close (eye 2.3 cm above it) and 1cm (eye 1 cm from
// the top of the drape, looking at it as close does). Per camera: one
// full-detail reference render, then `--detail view` renders with the level thresholds scaled by
// 0.5, 1 (the default) and 2 (a cell keeps a finer level down to half / twice the projected size),
// plus the default at a second seed (the noise floor of the view render), and the full render at a
// second seed (the noise floor of the comparison: how close another full render comes). Each gives the geometry
// kept (curve segments traced, surface triangles), wall time of scene + render, peak memory (the
// view's own: reset before each view render), the camera's distance to its target, and
// the image error against the reference: mean radiance per channel and the RMSE of 4 x 4 block
// mean luminances, both relative to the reference's mean.
// Built only with render_check (KNIT_BUILD_RENDER_CHECK).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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

// One `--detail view` render of camera c with thresholds scaled by `scale`.
json viewRender(const knit::Pattern& pattern, const knit::BaseMesh& mesh, const Camera& c, double scale, uint64_t seed,
                const knit::Image& reference, size_t fullSegments) {
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
    const knit::RenderResult r = knit::renderScene(scene, renderOptions(c, seed));
    json out = imageError(r.image, reference);
    out["threshold_scale"] = scale;
    out["seed"] = seed;
    out["seconds"] = seconds(t0);
    out["peak_bytes"] = knit::util::peakResidentBytes();
    out["segments"] = r.segments;
    out["surface_triangles"] = r.surfaceTriangles;
    out["segments_fraction"] = double(r.segments) / double(fullSegments);
    std::fprintf(stderr,
                 "  %s view x%.2g seed %llu: %.1f s, %zu segments (%.3g%% of full), %zu surface triangles, "
                 "mean %+.1f%% %+.1f%% %+.1f%%, block RMSE %.1f%%\n",
                 c.name, scale, static_cast<unsigned long long>(seed), out["seconds"].get<double>(), r.segments,
                 100.0 * out["segments_fraction"].get<double>(), r.surfaceTriangles,
                 100 * out["mean_relative"][0].get<double>(), 100 * out["mean_relative"][1].get<double>(),
                 100 * out["mean_relative"][2].get<double>(), 100 * out["block_rmse_relative"].get<double>());
    return out;
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
    // Step 1: the full-detail references (one scene with every ply, rendered from each camera).
    std::vector<knit::Image> references;
    json out;
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
    // Step 2: the view renders against them.
    for (size_t k = 0; k < cameras.size(); ++k) {
        json& runs = out[cameras[k].name]["view"] = json::array();
        for (const double scale : {0.5, 1.0, 2.0})
            runs.push_back(viewRender(pattern, mesh, cameras[k], scale, 1, references[k], fullSegments));
        runs.push_back(viewRender(pattern, mesh, cameras[k], 1.0, 2, references[k], fullSegments));
    }
    return out;
}

}  // namespace sve
