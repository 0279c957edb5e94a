// renderScene: validate, build tables and the Embree scene, place camera and light, render, write.
#include "knit/render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/image_io.hpp"
#include "knit/bake.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/scene.hpp"
#include "bsdf/material_overrides.hpp"
#include "render_budget.hpp"
#include "tracing/render_image.hpp"
#include "detail_geometry.hpp"
#include "render_view.hpp"
#include "scene_scale.hpp"
#include "tracing/trace_scene.hpp"
#include "tracing/trace_surface.hpp"
#include "util/math.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// An image path whose extension is not the format written to it (a .jpg holding PNG bytes).
void checkImageName(const std::string& path, const char* ext, const char* option, const char* format) {
    if (util::lowerExtension(path) != ext)
        throw Error(std::string("render: ") + option + " '" + path + "': only " + format +
                    " is written there (use a ." + ext + " name)");
}

// The largest projected yarn radius (pixels) of a view's surface-level cells (0 without any).
double surfaceYarnPixels(const Scene& scene) {
    if (!scene.detail()) return 0;
    const CellLevels& l = scene.detail()->levels;
    const double plyRadius = resolvePlyOptions(scene.plyOptions()).plyRadius;
    if (!(plyRadius > 0)) return 0;
    double ply = 0;
    for (size_t k = 0; k < l.level.size() && k < l.plyPixels.size(); ++k)
        if (l.level[k] == DetailLevel::Surface) ply = std::max(ply, l.plyPixels[k]);
    return ply * scene.yarnRadius() / plyRadius;
}

}  // namespace

const char* lightPlacementName(LightPlacement light) {
    switch (light) {
        case LightPlacement::Front: return "front";
        case LightPlacement::Back: return "back";
    }
    return "?";
}

PlyMaterial resolveMaterial(const RenderOptions& o) {
    PlyMaterial m = o.material;
    if (!o.materialFile.empty()) m = loadMaterialFile(o.materialFile, m);
    if (!o.materialOverrides.empty()) m = applyMaterialOverrides(o.materialOverrides, m, "material flags");
    validateMaterial(m, o.materialFile.empty() ? "material" : "material file '" + o.materialFile + "'");
    return m;
}

RenderResult renderScene(const Scene& scene, const RenderOptions& o) {
    // Step 0: a scene far from metre size is traced as a copy at unit size (any scale renders).
    if (const std::optional<Scene> scaled = impl::sceneAtTracingScale(scene)) return renderScene(*scaled, o);
    // Step 1: validate every option before any work.
    if (o.light != LightPlacement::Front && o.light != LightPlacement::Back)
        throw Error("render: unknown light placement " + std::to_string(int(o.light)) + " (expected front or back)");
    const GeometryMode mode = o.mode;
    if (mode != GeometryMode::Curves && mode != GeometryMode::Tubes && mode != GeometryMode::Grid)
        throw Error("render: unknown geometry mode " + std::to_string(int(mode)) + " (expected curves, tubes or grid)");
    if (o.spp < 1) throw Error("render: samples per pixel must be at least 1 (got " + std::to_string(o.spp) + ")");
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        throw Error("render: image size " + std::to_string(o.width) + " x " + std::to_string(o.height) +
                    " is outside 1..16384");
    if (o.maxDepth < 1 || o.maxDepth > 1000) throw Error("render: max depth must be in 1..1000");
    if (!(o.environment >= 0) || !(o.lightIrradiance >= 0) || !std::isfinite(o.environment) ||
        !std::isfinite(o.lightIrradiance))
        throw Error("render: environment and light irradiance must be finite and >= 0");
    if (!(o.fovDegrees > 1 && o.fovDegrees < 170)) throw Error("render: field of view must be in (1, 170) degrees");
    if (!(o.baseAlbedo >= 0 && o.baseAlbedo <= 1)) throw Error("render: base albedo must be in [0, 1]");
    if (mode == GeometryMode::Tubes && o.tubeSides < 3) throw Error("render: tube sides must be >= 3");
    RenderResult res;
    res.material = resolveMaterial(o);
    if (!o.surface && !scene.detail() &&
        (scene.plies().curves.curveCount() == 0 || scene.plies().curves.pointCount() == 0))
        throw Error("render: the scene has no ply curves (nothing to render; were plies built?)");
    if (o.surface && scene.mesh().faces.empty()) throw Error("render: the surface level needs a base mesh");
    const View view = renderView(scene, o);
    if (!o.output.empty()) checkImageName(o.output, "png", "--output", "PNG");
    if (!o.exr.empty()) checkImageName(o.exr, "exr", "--exr", "EXR");
    if (!o.output.empty()) checkWritable(o.output);
    if (!o.exr.empty()) checkWritable(o.exr);
    impl::checkRenderBudget(scene.plies(), o);
    res.mode = mode;
    res.light = o.light;
    res.spp = o.spp;
    // Step 2: ply segments (and a view's yarn-level curves) relative to the centre of the framed
    // bounds; a view's surface-level triangles (or, with --surface-only, the whole base mesh).
    const glm::dvec3 centre = framedBounds(scene.mesh(), impl::sceneMargin(scene)).centre;
    const PlyGeometry geometry =
        o.surface ? impl::surfaceFrame(scene, centre) : impl::renderCurves(scene, centre, res.material.fiberTwist);
    res.segments = geometry.segmentCount();
    const BaseMesh surface = impl::surfaceMesh(scene);
    res.surfaceTriangles = surface.faces.size();
    const BaseMesh* base = o.baseMesh || o.surface ? &scene.mesh() : (surface.faces.empty() ? nullptr : &surface);
    if (geometry.segmentCount() == 0 && base == nullptr)
        throw Error("render: the view sees none of the cloth (every cell is culled; check --eye and --target)");
    // A view's surface level: the pattern baked with the render's material, as --surface-only.
    SurfaceBake viewBake;
    SurfaceTexture viewTexture;
    if (!o.surface && !o.baseMesh && !surface.faces.empty()) {
        BakeOptions bo;
        bo.width = o.viewBakeSize > 0 ? o.viewBakeSize : viewBakeWidth(scene.pattern(), surfaceYarnPixels(scene));
        bo.plies = patternPlyOptions(scene.plyOptions(), scene.pattern(), scene.placement().scale);
        const glm::dvec2 stretch = placementStretch(scene.pattern(), scene.placement());
        bo.stretch[0] = stretch.x, bo.stretch[1] = stretch.y;
        bo.material = res.material;
        bo.scatteringPaths = o.surfaceScatteringPaths;
        // The table's paths go mostly where this view sees the surface level from and lights it from.
        const RectLight light = impl::defaultLight(scene, o.light, o.lightIrradiance);
        bo.scatteringFocus =
            impl::scatteringFocus(surface, view.eye, glm::dvec3(light.corner + 0.5 * (light.edgeU + light.edgeV)));
        viewBake = bakeSurface(scene.pattern(), bo);
        viewTexture = makeSurfaceTexture(viewBake, scene.placement().repeats);
        res.surfaceTextured = true;
        res.bakeSeconds = viewBake.seconds;
    }
    // Step 3: fiber tables.
    auto t0 = std::chrono::steady_clock::now();
    int plyCount = 1;
    for (uint8_t p : scene.plies().plyOfCurve) plyCount = std::max(plyCount, int(p) + 1);
    // Yarn-level curves shade as the bundle of the scene's plies (its crevice shadow), also when
    // no cell of the view is at the ply level.
    if (geometry.firstBundleSegment < geometry.segmentCount())
        plyCount = std::max(plyCount, resolvePlyOptions(scene.plyOptions()).count);
    const FiberTables tables = buildFiberTables(fiberTableOptions(res.material, plyCount));
    res.tableSeconds = secondsSince(t0);
    res.tableBytes = tables.bytes();
    // Step 4: Embree scene of the chosen mode.
    t0 = std::chrono::steady_clock::now();
    EmbreeDevice device;
    std::vector<int64_t> cells;
    TraceSceneOptions so;
    so.mode = mode;
    so.tubeSides = o.tubeSides;
    so.baseMesh = base;
    SurfaceTexture texture = impl::surfaceTexture(scene, o);
    so.baseTexture = o.surface ? &texture : res.surfaceTextured ? &viewTexture : nullptr;
    // Camera rays read the surface level's tint and holes prefiltered over their footprint.
    for (SurfaceTexture* t : {&texture, &viewTexture}) {
        t->pixelAngle = 2.0 * std::tan(view.fovDegrees * util::kPi / 360.0) / view.height;
        t->eye = geometry.toScene(view.eye);
    }
    if (mode == GeometryMode::Grid && !o.surface) {
        // A view with no curves (all surface: it built no yarns) has no segment to place.
        if (geometry.segmentCount() > 0) cells = segmentCells(scene, geometry);
        so.segmentCells = &cells;
    }
    const TraceScene traceScene(device, geometry, so);
    res.buildSeconds = secondsSince(t0);
    res.memory = traceScene.memory();
    res.primitives = traceScene.primitiveCount();
    // Step 5: camera and light (both from the base mesh grown by the yarns' margin).
    TraceSettings ts;
    ts.width = o.width, ts.height = o.height, ts.spp = o.spp, ts.seed = o.seed, ts.maxDepth = o.maxDepth;
    ts.camera = impl::cameraOf(view);
    ts.environment = Rgb(o.environment);
    // The surface level (no --base-mesh) is the cloth itself: its body colour.
    ts.baseAlbedo = o.baseMesh ? Rgb(o.baseAlbedo) : res.material.bodyAlbedo;
    ts.light = impl::defaultLight(scene, o.light, o.lightIrradiance);
    // Step 6: render, with progress on stderr for long renders.
    std::mutex progressMutex;
    int lastDecile = 0;
    if (o.progress && double(o.width) * o.height * o.spp > 1e6) {
        ts.progress = [&](double f) {
            std::lock_guard<std::mutex> lock(progressMutex);
            const int decile = static_cast<int>(f * 10);
            if (decile > lastDecile) {
                lastDecile = decile;
                std::fprintf(stderr, "render: %d%%\n", decile * 10);
            }
        };
    }
    res.camera = ts.camera;
    res.view = view;
    res.areaLight = ts.light;
    TraceStats stats;
    res.image = renderImage(traceScene, res.material, tables, ts, &stats);
    res.renderSeconds = stats.seconds;
    res.rays = stats.rays;
    res.raysPerSecond = stats.seconds > 0 ? stats.rays / stats.seconds : 0;
    // Step 7: images.
    if (!o.output.empty()) writePng(o.output, res.image), res.written.push_back(o.output);
    if (!o.exr.empty()) writeExr(o.exr, res.image), res.written.push_back(o.exr);
    res.peakMemoryBytes = int64_t(util::peakResidentBytes());
    return res;
}

int viewBakeWidth(const Pattern& pattern, double yarnPixels) {
    if (!(pattern.radius > 0) || !(pattern.px > 0) || !(yarnPixels > 0)) return 64;
    const double texels = std::min(4.0 * pattern.px / pattern.radius * yarnPixels, 256.0);  // N runs along px
    return std::clamp(16 * int(std::ceil(texels / 16.0)), 64, 256);
}

}  // namespace knit
