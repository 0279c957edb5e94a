// Yarn colours in the renderer: a red / blue stripe chart renders red and blue bands of courses.
#include <gtest/gtest.h>

#include <algorithm>

#include "knit/base_mesh.hpp"
#include "knit/chart.hpp"
#include "knit/chart_pattern.hpp"
#include "knit/ply_material.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

// The relaxed 2 x 2 stockinette, its bottom row red and its top row blue, on a plane.
Scene stripeScene(bool coloured) {
    const std::string text = coloured ? "k k\nk k\n\nB B\nA A\nA=#ff0000 B=#0000ff\n" : std::string("k k\nk k\n");
    SceneOptions o;
    o.placement.repeats = {2, 3};
    return buildScene(relaxChart(parseChart(text, "stripes.chart")).relaxed.pattern, makePlane(), o);
}

// (R - B) / (R + B) of the mean colour of every pixel row (axis 0) or column (axis 1).
std::vector<double> bandBalance(const Image& im, int axis) {
    const int lines = axis == 0 ? im.height : im.width, along = axis == 0 ? im.width : im.height;
    std::vector<double> out;
    for (int l = 0; l < lines; ++l) {
        Rgb sum(0.0);
        for (int a = 0; a < along; ++a) sum += axis == 0 ? im.pixel(a, l) : im.pixel(l, a);
        out.push_back(sum.r + sum.b > 0 ? (sum.r - sum.b) / (sum.r + sum.b) : 0.0);
    }
    return out;
}

// True when the lines along one image axis include clearly red and clearly blue bands.
bool hasRedAndBlueBands(const Image& im) {
    for (int axis = 0; axis < 2; ++axis) {
        const std::vector<double> b = bandBalance(im, axis);
        const auto [lo, hi] = std::minmax_element(b.begin(), b.end());
        if (*hi > 0.3 && *lo < -0.3) return true;
    }
    return false;
}

// A small, quick render of the stripe scene.
Image stripeImage(bool coloured) {
    RenderOptions o;
    o.width = o.height = 48;
    o.spp = 8;
    o.progress = false;
    return renderScene(stripeScene(coloured), o).image;
}

TEST(ColourRender, stripeChartRendersRedAndBlueBands) {
    const Image im = stripeImage(true);
    EXPECT_TRUE(hasRedAndBlueBands(im));
    // Both colours cover a good part of the image.
    int red = 0, blue = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const Rgb p = im.pixel(x, y);
            red += p.r > 2 * p.b && p.r > 0.01;
            blue += p.b > 2 * p.r && p.b > 0.01;
        }
    EXPECT_GT(red, im.width * im.height / 10);
    EXPECT_GT(blue, im.width * im.height / 10);
}

TEST(ColourRender, withoutColoursTheBodyColourIsUniform) {
    // The default body colour is brown (R > B) everywhere: no blue band.
    EXPECT_FALSE(hasRedAndBlueBands(stripeImage(false)));
}

TEST(ColourRender, yarnBodyAlbedoKeepsTheMaterialsBrightness) {
    PlyMaterial m;
    m.bodyAlbedo = Rgb(0.2, 0.5, 0.1);
    const Rgb a = yarnBodyAlbedo(m, glm::vec3(0.f, 0.f, 1.f));
    EXPECT_EQ(a, Rgb(0.0, 0.0, 0.5));
    EXPECT_EQ(yarnBodyAlbedo(m, glm::vec3(1.f)), Rgb(0.5));
}

}  // namespace
}  // namespace knit
