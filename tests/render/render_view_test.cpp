// renderScene with views: the camera used, and scenes built for a view (ply, yarn and surface levels).
#include <gtest/gtest.h>

#include <string>

#include "knit/error.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

RenderOptions tinyRender() {
    RenderOptions o;
    o.width = 32, o.height = 24, o.spp = 4, o.progress = false;
    return o;
}

SceneOptions plane(const std::optional<DetailOptions>& detail) {
    SceneOptions so;
    so.mesh = "plane";
    so.placement.repeats = {6, 6};
    so.meshOptions.resU = so.meshOptions.resV = 4;
    so.detail = detail;
    return so;
}

TEST(RenderView, defaultCameraFramesTheBaseMeshGrownByTheYarnMargin) {
    const Scene s = buildScene(plane(std::nullopt));
    const RenderOptions o = tinyRender();
    View settings;
    settings.fovDegrees = o.fovDegrees, settings.width = o.width, settings.height = o.height;
    const View expected = frameMesh(s.mesh(), yarnMargin(s.binding(), s.yarnRadius()), settings);
    const RenderResult r = renderScene(s, o);
    EXPECT_EQ(r.camera.eye, expected.eye);
    EXPECT_EQ(r.camera.target, expected.target);
    // A given camera is used as given.
    RenderOptions given = o;
    View v = expected;
    v.eye += glm::dvec3(0.1, 0.0, 0.0);
    given.view = v;
    EXPECT_EQ(renderScene(s, given).camera.eye, v.eye);
    v.target = v.eye;
    given.view = v;
    try {
        renderScene(s, given);
        FAIL() << "eye = target accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--eye and --target must differ"), std::string::npos);
    }
}

TEST(RenderView, farViewRendersOnlyTheSurfaceLevel) {
    DetailOptions d;
    d.viewSettings.width = 32, d.viewSettings.height = 24;
    // The default framing at 32 x 24: a pixel is ~3 cm of a 0.5 m plane, a yarn ~1 cm wide.
    const Scene s = buildScene(plane(d));
    RenderOptions o = tinyRender();
    const RenderResult r = renderScene(s, o);
    EXPECT_EQ(r.segments, 0u);
    EXPECT_GT(r.surfaceTriangles, 0u);
    EXPECT_GT(r.image.mean().x, 0.0);
    EXPECT_EQ(s.plies().curves.pointCount(), 0u);
}

TEST(RenderView, yarnLevelIsDrawnAsCurvesOnly) {
    DetailOptions d;
    d.viewSettings.width = 32, d.viewSettings.height = 24;
    d.plyPixels = {1e9, 1e9};   // never plies
    d.yarnPixels = {0.0, 0.0};  // always yarns
    const Scene s = buildScene(plane(d));
    ASSERT_GT(s.detail()->pieces.yarns.curves.pointCount(), 0u);
    RenderOptions o = tinyRender();
    const RenderResult r = renderScene(s, o);
    EXPECT_GT(r.segments, 0u);
    EXPECT_GT(r.image.mean().x, 0.0);
    o.mode = GeometryMode::Tubes;
    EXPECT_THROW(renderScene(s, o), Error);
}

}  // namespace
}  // namespace knit
