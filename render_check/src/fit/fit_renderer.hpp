// fit_renderer.hpp (internal) — renders one scene many times with different materials, as the fit
// does, without rebuilding what the material does not change: the ply geometry and the Embree
// scene (rebuilt only when the fiber twist changes) and the fiber tables (rebuilt only when their
// inputs change). The view (camera and area light of each lighting) is taken from renderScene
// itself, so every image equals renderScene's for the same options bit for bit (fit_test pins it).
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "knit/fiber_tables.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"
#include "render/scene_scale.hpp"

namespace knit {

class EmbreeDevice;
class TraceScene;

class FitRenderer {
public:
    // `options` fixes the view, lights, geometry mode and tracer settings (its material, size, spp
    // and light are given per render). The scene must outlive the renderer.
    FitRenderer(const Scene& scene, const RenderOptions& options);
    ~FitRenderer();
    FitRenderer(const FitRenderer&) = delete;
    FitRenderer& operator=(const FitRenderer&) = delete;

    // The image renderScene would make with these options (validated material).
    Image render(const PlyMaterial& material, LightPlacement light, int width, int height, int spp);

private:
    void prepareGeometry(double fiberTwist);
    const FiberTables& tablesFor(const PlyMaterial& material);

    std::optional<impl::TracingCopy> scaled_;  // the scene at tracing scale when it is far from metre size
    const Scene* scene_ = nullptr;
    RenderOptions options_;
    glm::dvec3 centre_{0.0};
    int plyCount_ = 1;
    std::map<LightPlacement, std::pair<Camera, RectLight>> views_;
    std::unique_ptr<EmbreeDevice> device_;
    std::optional<double> twist_;  // the fiber twist the geometry was built for
    PlyGeometry geometry_;
    std::vector<int64_t> cells_;
    std::unique_ptr<TraceScene> trace_;
    std::optional<FiberTableOptions> tableKey_;
    FiberTables tables_;
};

}  // namespace knit
