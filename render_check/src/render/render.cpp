// renderScene as named phases: rescale for tracing, validate, place the geometry, bake a view's
// surface level, fiber tables, the Embree scene, trace (camera, light, progress), write the images.
#include "knit/render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>

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
void checkImageName(const std::string& path, const char* ext, const char* setting, const char* format) {
    if (util::lowerExtension(path) != ext)
        throw Error(std::string("cannot render: ") + setting + " '" + path + "': only " + format +
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

// One render of a scene: renderScene runs the phases in order, each reading what the ones before
// it made and filling its part of the result. Everything traced is in traced_'s units (the scene at
// tracing scale); what the pattern decides (the bake, the texture's repeats, the yarns' margin) is
// the scene's own; the camera and light reported are in metres.
class SceneRender {
public:
    SceneRender(const Scene& scene, const RenderOptions& o) : scene_(scene), o_(o) {}

    // A scene far from metre size is traced as a copy at unit size (any scale renders).
    void rescaleForTracing() {
        copy_ = impl::sceneAtTracingScale(scene_);
        if (copy_) traced_ = &copy_->scene, scale_ = copy_->scale;
    }

    // Validate every option, the material, the scene, the view, the image paths and the memory
    // budget before any work.
    void validate() {
        if (o_.light != LightPlacement::Front && o_.light != LightPlacement::Back)
            throw Error("cannot render: unknown light placement " + std::to_string(int(o_.light)) +
                        " (expected front or back)");
        const GeometryMode mode = o_.mode;
        if (mode != GeometryMode::Curves && mode != GeometryMode::Tubes && mode != GeometryMode::Grid)
            throw Error("cannot render: unknown geometry mode " + std::to_string(int(mode)) +
                        " (expected curves, tubes or grid)");
        if (o_.spp < 1)
            throw Error("cannot render: samples per pixel must be at least 1 (got " + std::to_string(o_.spp) + ")");
        if (o_.width < 1 || o_.height < 1 || o_.width > 16384 || o_.height > 16384)
            throw Error("cannot render: image size " + std::to_string(o_.width) + " x " + std::to_string(o_.height) +
                        " is outside 1..16384");
        if (o_.maxDepth < 1 || o_.maxDepth > 1000) throw Error("cannot render: max depth must be in 1..1000");
        // The image and its EXR hold 32-bit floats: a radiance near their range (3.4e38) would sum
        // to inf over the samples of a pixel and leave a non-finite image.
        for (const auto& [value, words] : {std::pair{o_.environment, "the environment radiance"},
                                           std::pair{o_.lightIrradiance, "the light irradiance"}})
            if (!(value >= 0 && value <= 1e30)) {
                std::ostringstream m;
                m << "cannot render: " << words << " " << value
                  << " must be a number in 0..1e30 (images hold 32-bit floats)";
                throw Error(m.str());
            }
        if (!(o_.fovDegrees > 1 && o_.fovDegrees < 170))
            throw Error("cannot render: field of view must be in (1, 170) degrees");
        if (!(o_.baseAlbedo >= 0 && o_.baseAlbedo <= 1)) throw Error("cannot render: base albedo must be in [0, 1]");
        if (mode == GeometryMode::Tubes && o_.tubeSides < 3) throw Error("cannot render: tube sides must be >= 3");
        res_.material = resolveMaterial(o_);
        if (!o_.surface && !scene_.detail() &&
            (scene_.plies().curves.curveCount() == 0 || scene_.plies().curves.pointCount() == 0))
            throw Error("cannot render: the scene has no ply curves (nothing to render; were plies built?)");
        if (o_.surface && scene_.mesh().faces.empty())
            throw Error("cannot render: the surface level needs a base mesh");
        frame_ = impl::tracedFrame(scene_, traced_->mesh(), scale_, o_);
        if (!o_.output.empty()) checkImageName(o_.output, "png", "the output image", "PNG");
        if (!o_.exr.empty()) checkImageName(o_.exr, "exr", "the EXR image", "EXR");
        if (!o_.output.empty()) checkWritable(o_.output);
        if (!o_.exr.empty()) checkWritable(o_.exr);
        impl::checkRenderBudget(scene_.plies(), o_);
        res_.mode = mode;
        res_.light = o_.light;
        res_.spp = o_.spp;
    }

    // Ply segments (and a view's yarn-level curves) relative to the centre of the framed bounds;
    // a view's surface-level triangles (or, with --surface-only, the whole base mesh).
    void placeGeometry() {
        const glm::dvec3& centre = frame_.centre;
        geometry_ = o_.surface ? impl::surfaceFrame(*traced_, centre)
                               : impl::renderCurves(*traced_, centre, res_.material.fiberTwist);
        res_.segments = geometry_.segmentCount();
        surface_ = impl::surfaceMesh(*traced_);
        res_.surfaceTriangles = surface_.faces.size();
        base_ = o_.baseMesh || o_.surface ? &traced_->mesh() : (surface_.faces.empty() ? nullptr : &surface_);
        if (geometry_.segmentCount() == 0 && base_ == nullptr)
            throw Error(
                "cannot render: the view sees none of the cloth (every cell is culled; check the eye position and the "
                "target position)");
    }

    // A view's surface level: the pattern baked with the render's material, as --surface-only.
    void bakeViewSurface() {
        if (o_.surface || o_.baseMesh || surface_.faces.empty()) return;
        BakeOptions bo;
        bo.width = o_.viewBakeSize > 0 ? o_.viewBakeSize : viewBakeWidth(scene_.pattern(), surfaceYarnPixels(scene_));
        bo.plies = patternPlyOptions(scene_.plyOptions(), scene_.pattern(), scene_.placement().scale);
        const glm::dvec2 stretch = placementStretch(scene_.pattern(), scene_.placement());
        bo.stretch[0] = stretch.x, bo.stretch[1] = stretch.y;
        bo.material = res_.material;
        bo.scatteringPaths = o_.surfaceScatteringPaths;
        // The table's paths go mostly where this view sees the surface level from and lights it from.
        const RectLight& light = frame_.light;
        bo.scatteringFocus = impl::scatteringFocus(surface_, frame_.view.eye,
                                                   glm::dvec3(light.corner + 0.5 * (light.edgeU + light.edgeV)));
        viewBake_ = bakeSurface(scene_.pattern(), bo);
        viewTexture_ = makeSurfaceTexture(viewBake_, scene_.placement().repeats);
        res_.surfaceTextured = true;
        res_.bakeSeconds = viewBake_.seconds;
    }

    // Fiber tables for the plies of a yarn (at least the scene's count when yarn-level curves
    // shade as the bundle of its plies).
    void buildTables() {
        const auto t0 = std::chrono::steady_clock::now();
        int plyCount = 1;
        for (uint8_t p : traced_->plies().plyOfCurve) plyCount = std::max(plyCount, int(p) + 1);
        // Yarn-level curves shade as the bundle of the scene's plies (its crevice shadow), also when
        // no cell of the view is at the ply level.
        if (geometry_.firstBundleSegment < geometry_.segmentCount())
            plyCount = std::max(plyCount, resolvePlyOptions(scene_.plyOptions()).count);
        tables_ = buildFiberTables(fiberTableOptions(res_.material, plyCount));
        res_.tableSeconds = secondsSince(t0);
        res_.tableBytes = tables_.bytes();
    }

    // The Embree scene of the chosen mode plus the drawn base mesh and its surface texture.
    void buildTraceScene() {
        const auto t0 = std::chrono::steady_clock::now();
        device_.emplace();
        TraceSceneOptions so;
        so.mode = o_.mode;
        so.tubeSides = o_.tubeSides;
        so.baseMesh = base_;
        texture_ = impl::surfaceTexture(scene_, o_);
        so.baseTexture = o_.surface ? &texture_ : res_.surfaceTextured ? &viewTexture_ : nullptr;
        // Camera rays read the surface level's tint and holes prefiltered over their footprint.
        for (SurfaceTexture* t : {&texture_, &viewTexture_}) {
            t->pixelAngle = 2.0 * std::tan(frame_.view.fovDegrees * util::kPi / 360.0) / frame_.view.height;
            t->eye = geometry_.toScene(frame_.view.eye);
        }
        if (o_.mode == GeometryMode::Grid && !o_.surface) {
            // A view with no curves (all surface: it built no yarns) has no segment to place.
            if (geometry_.segmentCount() > 0) cells_ = segmentCells(*traced_, geometry_);
            so.segmentCells = &cells_;
        }
        traceScene_.emplace(*device_, geometry_, so);
        res_.buildSeconds = secondsSince(t0);
        res_.memory = traceScene_->memory();
        res_.primitives = traceScene_->primitiveCount();
    }

    // Camera and light (both from the base mesh grown by the yarns' margin), then the image, with
    // progress on stderr for long renders.
    void trace() {
        TraceSettings ts;
        ts.width = o_.width, ts.height = o_.height, ts.spp = o_.spp, ts.seed = o_.seed, ts.maxDepth = o_.maxDepth;
        ts.camera = impl::cameraOf(frame_.view);
        ts.environment = Rgb(o_.environment);
        // The surface level (no --base-mesh) is the cloth itself: its body colour.
        ts.baseAlbedo = o_.baseMesh ? Rgb(o_.baseAlbedo) : res_.material.bodyAlbedo;
        ts.light = frame_.light;
        std::mutex progressMutex;
        int lastDecile = 0;
        if (o_.progress && double(o_.width) * o_.height * o_.spp > 1e6) {
            ts.progress = [&](double f) {
                std::lock_guard<std::mutex> lock(progressMutex);
                const int decile = static_cast<int>(f * 10);
                if (decile > lastDecile) {
                    lastDecile = decile;
                    std::fprintf(stderr, "render: %d%%\n", decile * 10);
                }
            };
        }
        res_.view = scale_.worldView(frame_.view);
        res_.camera = impl::cameraOf(res_.view);
        res_.areaLight = scale_.worldLight(frame_.light);
        TraceStats stats;
        res_.image = renderImage(*traceScene_, res_.material, tables_, ts, &stats);
        res_.renderSeconds = stats.seconds;
        res_.rays = stats.rays;
        res_.raysPerSecond = stats.seconds > 0 ? stats.rays / stats.seconds : 0;
    }

    // The PNG and EXR files asked for.
    void writeImages() {
        if (!o_.output.empty()) writePng(o_.output, res_.image), res_.written.push_back(o_.output);
        if (!o_.exr.empty()) writeExr(o_.exr, res_.image), res_.written.push_back(o_.exr);
        res_.peakMemoryBytes = int64_t(util::peakResidentBytes());
    }

    RenderResult result() { return std::move(res_); }

private:
    const Scene& scene_;
    const RenderOptions& o_;
    std::optional<impl::TracingCopy> copy_;  // the scene at unit size when it is far from metre size
    const Scene* traced_ = &scene_;          // the scene traced: copy_ or scene_
    impl::TracingScale scale_;               // metres to traced_'s units (the identity without a copy)
    RenderResult res_;
    impl::TracedFrame frame_;         // view, light and geometry origin in traced_'s units
    PlyGeometry geometry_;            // plies and yarn-level curves in scene units
    BaseMesh surface_;                // a view's surface-level triangles
    const BaseMesh* base_ = nullptr;  // the base mesh drawn (the whole mesh, surface_ or none)
    SurfaceBake viewBake_;            // a view's surface level baked
    SurfaceTexture viewTexture_;      // its texture
    SurfaceTexture texture_;          // the texture of RenderOptions::surface
    FiberTables tables_;
    std::optional<EmbreeDevice> device_;
    std::vector<int64_t> cells_;  // grid mode: the cell of each segment
    std::optional<TraceScene> traceScene_;
};
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
    if (!o.materialOverrides.empty()) m = applyMaterialOverrides(o.materialOverrides, m, "the material overrides");
    validateMaterial(m, o.materialFile.empty() ? "material" : "material file '" + o.materialFile + "'");
    return m;
}

RenderResult renderScene(const Scene& scene, const RenderOptions& o) {
    SceneRender render(scene, o);
    render.rescaleForTracing();
    render.validate();
    render.placeGeometry();
    render.bakeViewSurface();
    render.buildTables();
    render.buildTraceScene();
    render.trace();
    render.writeImages();
    return render.result();
}

int viewBakeWidth(const Pattern& pattern, double yarnPixels) {
    if (!(pattern.radius > 0) || !(pattern.px > 0) || !(yarnPixels > 0)) return 64;
    const double texels = std::min(4.0 * pattern.px / pattern.radius * yarnPixels, 256.0);  // N runs along px
    return std::clamp(16 * int(std::ceil(texels / 16.0)), 64, 256);
}

}  // namespace knit
