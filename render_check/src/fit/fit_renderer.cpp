// FitRenderer: the view from renderScene once per lighting, then geometry, Embree scene and fiber
// tables kept while the material leaves them unchanged.
#include "fit_renderer.hpp"

#include <algorithm>
#include <tuple>

#include <glm/common.hpp>

#include "knit/view.hpp"
#include "tracing/render_image.hpp"
#include "render/render_view.hpp"
#include "render/scene_scale.hpp"
#include "tracing/trace_scene.hpp"

namespace knit {
namespace {

bool sameTables(const FiberTableOptions& a, const FiberTableOptions& b) {
    return std::tie(a.fiberCount, a.plyCount, a.size, a.aoRays, a.fiberShadowFloor, a.plyShadowFloor) ==
           std::tie(b.fiberCount, b.plyCount, b.size, b.aoRays, b.fiberShadowFloor, b.plyShadowFloor);
}

}  // namespace

FitRenderer::FitRenderer(const Scene& scene, const RenderOptions& options) : options_(options) {
    // Step 1: the scene as renderScene traces it (scaled copy far from metre size).
    scaled_ = impl::sceneAtTracingScale(scene);
    scene_ = scaled_ ? &scaled_->scene : &scene;
    const impl::TracingScale scale = scaled_ ? scaled_->scale : impl::TracingScale{};
    options_.materialFile.clear(), options_.materialOverrides.clear();
    options_.output.clear(), options_.exr.clear(), options_.progress = false;
    // Step 2: the view of each lighting and the geometry's origin as renderScene frames them (in
    // the traced scene's units), after a one-sample renderScene has checked the options.
    for (LightPlacement light : {LightPlacement::Front, LightPlacement::Back}) {
        RenderOptions o = options_;
        o.light = light, o.width = 4, o.height = 3, o.spp = 1;
        renderScene(scene, o);
        const impl::TracedFrame frame = impl::tracedFrame(scene, scene_->mesh(), scale, o);
        views_[light] = {impl::cameraOf(frame.view), frame.light};
        centre_ = frame.centre;
    }
    // Step 3: the ply count (the tables').
    for (uint8_t p : scene_->plies().plyOfCurve) plyCount_ = std::max(plyCount_, int(p) + 1);
    device_ = std::make_unique<EmbreeDevice>();
}

FitRenderer::~FitRenderer() = default;

void FitRenderer::prepareGeometry(double fiberTwist) {
    if (twist_ && *twist_ == fiberTwist) return;
    trace_.reset();
    geometry_ = buildPlyGeometry(scene_->plies(), centre_, fiberTwist);
    TraceSceneOptions so;
    so.mode = options_.mode;
    so.tubeSides = options_.tubeSides;
    so.baseMesh = options_.baseMesh ? &scene_->mesh() : nullptr;
    if (options_.mode == GeometryMode::Grid) {
        cells_ = segmentCells(*scene_, geometry_);
        so.segmentCells = &cells_;
    }
    trace_ = std::make_unique<TraceScene>(*device_, geometry_, so);
    twist_ = fiberTwist;
}

const FiberTables& FitRenderer::tablesFor(const PlyMaterial& material) {
    const FiberTableOptions key = fiberTableOptions(material, plyCount_);
    if (!tableKey_ || !sameTables(*tableKey_, key)) tables_ = buildFiberTables(key), tableKey_ = key;
    return tables_;
}

Image FitRenderer::render(const PlyMaterial& material, LightPlacement light, int width, int height, int spp) {
    validateMaterial(material, "fitted material");
    prepareGeometry(material.fiberTwist);
    TraceSettings ts;
    ts.width = width, ts.height = height, ts.spp = spp, ts.seed = options_.seed, ts.maxDepth = options_.maxDepth;
    ts.camera = views_.at(light).first;
    ts.light = views_.at(light).second;
    ts.environment = Rgb(options_.environment);
    ts.baseAlbedo = Rgb(options_.baseAlbedo);
    return renderImage(*trace_, material, tablesFor(material), ts);
}

}  // namespace knit
