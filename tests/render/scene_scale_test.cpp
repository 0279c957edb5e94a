// Renders at any scale (render/scene_scale.hpp): a scene far from metre size is traced as a copy at
// unit size. The copy is made with Scene::fromParts, which holds no pattern or placement; what
// baking and shading read from those, from the ply options and from the yarns' margin must still
// be the scene's own, so a garment far larger than the tracing range renders as its metre-size
// twin does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "knit/render.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

// 0.5 m -> 50 km and 5 micrometres: bounding radii beyond kMaxTracedRadius and below kMinTracedRadius.
constexpr double kFactors[] = {1e5, 1e-5};

// A plane of `size` metres with `repeats` x `repeats` pattern periods: the pattern scales with it.
SceneOptions plane(double size, const std::optional<DetailOptions>& detail, double repeats = 6) {
    SceneOptions so;
    so.mesh = "plane";
    so.meshOptions.size = size;
    so.meshOptions.resU = so.meshOptions.resV = 4;
    so.placement.repeats = {repeats, repeats};
    so.plies.count = 3;  // not the default: the copy must keep it
    so.detail = detail;
    return so;
}

RenderOptions tinyRender() {
    RenderOptions o;
    o.width = 32, o.height = 24, o.spp = 8, o.progress = false;
    o.surfaceScatteringPaths = 256;
    return o;
}

// A point or vector of the scaled scene is k times the metre-size one's (up to rounding).
bool scaledBy(double k, const glm::dvec3& scaled, const glm::dvec3& home) {
    return glm::length(scaled - k * home) <= 1e-9 * k * (1 + glm::length(home));
}

// The images agree within noise (both mean and per pixel), the reported camera and light are in
// the scene's own units.
void expectScaledTwin(double k, const RenderResult& home, const RenderResult& big, const char* what) {
    ASSERT_EQ(home.image.rgb.size(), big.image.rgb.size()) << what;
    double diff = 0, sum = 0;
    for (size_t i = 0; i < home.image.rgb.size(); ++i) {
        ASSERT_TRUE(std::isfinite(big.image.rgb[i])) << what;
        diff += std::abs(double(home.image.rgb[i]) - big.image.rgb[i]);
        sum += home.image.rgb[i];
    }
    std::printf("%s: mean red %.5f at 0.5 m, %.5f at %g m; mean |difference| %.2f%%\n", what, home.image.mean().x,
                big.image.mean().x, 0.5 * k, 100 * diff / sum);
    EXPECT_GT(sum, 0) << what;
    EXPECT_LT(diff, 0.02 * sum) << what;
    EXPECT_TRUE(scaledBy(k, big.camera.eye, home.camera.eye)) << what << ": the camera in metres";
    EXPECT_TRUE(scaledBy(k, big.camera.target, home.camera.target)) << what;
    EXPECT_TRUE(scaledBy(k, big.areaLight.corner, home.areaLight.corner)) << what << ": the light in metres";
    EXPECT_TRUE(scaledBy(k, big.areaLight.edgeU, home.areaLight.edgeU)) << what;
    EXPECT_EQ(big.surfaceTextured, home.surfaceTextured) << what;
    EXPECT_EQ(big.segments, home.segments) << what;
}

// A far view (every cell at the surface level): the surface level is the pattern baked with the
// scene's pattern, placement and ply options.
TEST(SceneScale, farViewOfAGarmentBeyondTheTracingRangeRendersAsAtMetreSize) {
    DetailOptions d;
    d.viewSettings.width = 32, d.viewSettings.height = 24;
    const Scene home = buildScene(plane(0.5, d));
    ASSERT_GT(home.detail()->pieces.surfaceFaces.size(), 0u);
    const RenderResult h = renderScene(home, tinyRender());
    ASSERT_TRUE(h.surfaceTextured);
    for (const double k : kFactors)
        expectScaledTwin(k, h, renderScene(buildScene(plane(0.5 * k, d)), tinyRender()), "far view");
}

// A close view with plies near the eye and the yarn level beyond (its radius and crevice shadow
// from the ply options: 3 plies).
TEST(SceneScale, closeViewWithYarnLevelRendersAsAtMetreSize) {
    RenderOptions o = tinyRender();
    DetailOptions d;
    View v;
    v.eye = glm::dvec3(0.004, 0.03, 0.0), v.target = glm::dvec3(0.0), v.up = glm::dvec3(0, 0, -1);
    v.fovDegrees = o.fovDegrees, v.width = o.width, v.height = o.height;
    d.view = v;
    d.plyPixels = {3.0, 3.0};   // plies near the eye only
    d.yarnPixels = {0.0, 0.0};  // yarns everywhere else
    const Scene home = buildScene(plane(0.5, d, 40));
    ASSERT_GT(home.detail()->pieces.yarns.curves.pointCount(), 0u);
    ASSERT_GT(home.plies().curves.pointCount(), 0u);
    const RenderResult h = renderScene(home, o);
    // 50 km only: at 5 micrometres buildScene gives this view no ply-level cell (the levels of
    // detail are not scale-free; libknit's, not the render's).
    const double k = kFactors[0];
    DetailOptions scaled = d;
    scaled.view->eye *= k, scaled.view->target *= k;
    expectScaledTwin(k, h, renderScene(buildScene(plane(0.5 * k, scaled, 40)), o), "close view, yarn level");
}

// The whole scene (no view), framed by the default camera (the yarns' margin) and seen through a
// camera given in metres.
TEST(SceneScale, wholeSceneRendersAsAtMetreSizeWithTheDefaultAndAGivenCamera) {
    const Scene home = buildScene(plane(0.5, std::nullopt));
    RenderOptions o = tinyRender();
    const RenderResult h = renderScene(home, o);
    View v = h.view;
    v.eye = glm::dvec3(0.05, 0.12, 0.1), v.target = glm::dvec3(0.02, 0.0, 0.0);
    RenderOptions given = o;
    given.view = v;
    const RenderResult hv = renderScene(home, given);
    for (const double k : kFactors) {
        const Scene scaled = buildScene(plane(0.5 * k, std::nullopt));
        expectScaledTwin(k, h, renderScene(scaled, o), "whole scene, default camera");
        given.view->eye = k * v.eye, given.view->target = k * v.target;
        expectScaledTwin(k, hv, renderScene(scaled, given), "whole scene, given camera");
    }
}

}  // namespace
}  // namespace knit
