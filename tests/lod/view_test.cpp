// knit::View: validation naming the options, projection, frustum planes, pixel footprint, framing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/fixtures.hpp"
#include "knit/error.hpp"
#include "knit/view.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

View lookDownZ() {
    View v;
    v.eye = {0, 0, 2};
    v.target = {0, 0, 0};
    v.up = {0, 1, 0};
    v.fovDegrees = 90;
    v.width = 200, v.height = 100;
    return v;
}

std::string errorOf(const View& v) {
    try {
        validateView(v);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(View, badViewsNameTheSetting) {
    View v = lookDownZ();
    EXPECT_EQ(errorOf(v), "");
    v.target = v.eye;
    EXPECT_NE(errorOf(v).find("the eye position and the target position must differ"), std::string::npos);
    v = lookDownZ(), v.up = {0, 0, 5};
    EXPECT_NE(errorOf(v).find("the up direction must not be parallel"), std::string::npos);
    for (double fov : {0.0, -5.0, 180.0, 200.0}) {
        v = lookDownZ(), v.fovDegrees = fov;
        EXPECT_NE(errorOf(v).find("the field of view"), std::string::npos) << fov;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    v = lookDownZ(), v.eye.y = nan;
    EXPECT_NE(errorOf(v).find("the eye position"), std::string::npos);
    v = lookDownZ(), v.target.x = inf;
    EXPECT_NE(errorOf(v).find("the target position"), std::string::npos);
    v = lookDownZ(), v.up.z = nan;
    EXPECT_NE(errorOf(v).find("the up direction"), std::string::npos);
    v = lookDownZ(), v.fovDegrees = nan;
    EXPECT_NE(errorOf(v).find("the field of view"), std::string::npos);
    v = lookDownZ(), v.width = 0;
    EXPECT_NE(errorOf(v).find("the image width"), std::string::npos);
    v = lookDownZ(), v.height = -3;
    EXPECT_NE(errorOf(v).find("the image height"), std::string::npos);
}

TEST(View, targetProjectsToImageCentreAndEdgesToBorders) {
    const View v = lookDownZ();
    const glm::dvec3 c = projectToPixel(v, {0, 0, 0});
    EXPECT_NEAR(c.x, 100, 1e-9);
    EXPECT_NEAR(c.y, 50, 1e-9);
    EXPECT_NEAR(c.z, 2, 1e-12);
    // fov 90: at depth 2 the image is 4 high, 8 wide; +y is up (row 0), +x right.
    const glm::dvec3 top = projectToPixel(v, {0, 2, 0}), right = projectToPixel(v, {4, 0, 0});
    EXPECT_NEAR(top.y, 0, 1e-9);
    EXPECT_NEAR(right.x, 200, 1e-9);
    EXPECT_LT(projectToPixel(v, {0, 0, 3}).z, 0);  // behind the eye
}

TEST(View, frustumPlanesAgreeWithProjection) {
    for (bool ortho : {false, true}) {
        View v = lookDownZ();
        v.orthographic = ortho, v.orthoHeight = 3;
        const std::array<Plane, 5> planes = frustumPlanes(v);
        for (int i = -6; i <= 6; ++i)
            for (int j = -6; j <= 6; ++j)
                for (double z : {-1.0, 0.0, 1.0}) {
                    const glm::dvec3 p(0.7 * i, 0.45 * j, z);
                    const glm::dvec3 px = projectToPixel(v, p);
                    const bool inImage = px.z > 0 && px.x > 0 && px.x < v.width && px.y > 0 && px.y < v.height;
                    bool inPlanes = true;
                    for (const Plane& pl : planes) inPlanes = inPlanes && pl.distance(p) > 0;
                    EXPECT_EQ(inImage, inPlanes) << ortho << " " << p.x << " " << p.y << " " << p.z;
                }
    }
}

TEST(View, pixelFootprintGrowsWithDepthUnlessOrthographic) {
    View v = lookDownZ();
    EXPECT_NEAR(pixelFootprint(v, 2.0), 4.0 / 100, 1e-12);  // 4 m image height over 100 px
    EXPECT_NEAR(pixelFootprint(v, 4.0), 8.0 / 100, 1e-12);
    v.orthographic = true, v.orthoHeight = 3;
    EXPECT_NEAR(pixelFootprint(v, 2.0), pixelFootprint(v, 40.0), 1e-15);
}

TEST(View, frameMeshLooksAtTheGrownBoundsAlongTheFront) {
    const BaseMesh m = test::planeMesh(test::Triangulation::Regular, 4, 1.0);  // z = 0, normal +z
    View settings = lookDownZ();
    settings.fovDegrees = 30;
    const View v = frameMesh(m, 0.1, settings);
    EXPECT_NEAR(v.target.x, 0.5, 1e-12);
    EXPECT_NEAR(v.target.z, 0.0, 1e-12);
    EXPECT_NEAR(v.eye.x, 0.5, 1e-12);
    EXPECT_GT(v.eye.z, 1.0);  // in front of the cloth (+z)
    const double radius = 0.5 * glm::length(glm::dvec3(1.0, 1.0, 0.0)) + 0.1;
    EXPECT_NEAR(glm::distance(v.eye, v.target), radius / std::sin(15.0 * knit::util::kPi / 180.0), 1e-9);
    EXPECT_EQ(v.width, settings.width);
    EXPECT_NO_THROW(validateView(v));
}

}  // namespace
}  // namespace knit
