// The surface level in the tracer: the base mesh shaded with a bake (RenderOptions::surface):
// the texture's orientation and repeat, the alpha MASK, the albedo, the transmittance.
#include <gtest/gtest.h>

#include <cstdio>

#include "knit/bake.hpp"
#include "knit/render.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

// A plane (+y up, u along +x, v along -z) without plies: what the surface level needs.
Scene planeScene() {
    SceneParts parts;
    parts.mesh = makePlane();
    parts.normals = vertexNormals(parts.mesh.positions, parts.mesh.faces);
    parts.yarnRadius = 0.001;
    return Scene::fromParts(std::move(parts));
}

// A 2 x 2 bake (row 0 at the top) of the given colours and coverages.
SurfaceBake quadrants(const std::vector<Rgb>& colours, const std::vector<float>& coverage) {
    SurfaceBake b;
    b.width = b.height = 2;
    for (const Rgb& c : colours) b.albedo.insert(b.albedo.end(), {float(c.r), float(c.g), float(c.b)});
    b.coverage = coverage;
    b.normal.assign(12, 0.f);
    b.heights.assign(4, 0.f);
    return b;
}

RenderOptions surfaceRender(const SurfaceBake& bake) {
    RenderOptions o;
    o.width = o.height = 24;
    o.spp = 4;
    o.progress = false;
    o.surface = &bake;
    o.surfaceRepeats[0] = o.surfaceRepeats[1] = 1;
    o.material.tableSize = 64, o.material.aoRays = 16;  // no plies are shaded
    return o;
}

// The texture's top-left texel lands at the image's top-left: the image's right is +u and its
// up +v, as on the ply level (texture coordinates (u, 1 - v), row 0 at the top).
TEST(SurfaceRender, textureQuadrantsLandWhereTheirUvIs) {
    const Rgb red(0.8, 0.05, 0.05), green(0.05, 0.8, 0.05), blue(0.05, 0.05, 0.8), grey(0.4);
    const SurfaceBake bake = quadrants({red, green, blue, grey}, {1, 1, 1, 1});
    const Scene scene = planeScene();
    const RenderResult r = renderScene(scene, surfaceRender(bake));
    auto dominant = [&](int x, int y) {
        const Rgb p = r.image.pixel(x, y);
        return p.r > 2 * std::max(p.g, p.b)   ? 0
               : p.g > 2 * std::max(p.r, p.b) ? 1
               : p.b > 2 * std::max(p.r, p.g) ? 2
                                              : 3;
    };
    // The plane fills the middle of the frame: sample well inside each quadrant.
    EXPECT_EQ(dominant(9, 9), 0);    // top left: red
    EXPECT_EQ(dominant(14, 9), 1);   // top right: green
    EXPECT_EQ(dominant(9, 14), 2);   // bottom left: blue
    EXPECT_EQ(dominant(14, 14), 3);  // bottom right: grey
}

// Coverage below the MASK cutoff lets every ray through: only the environment is seen.
TEST(SurfaceRender, uncoveredTexelsAreHolesInTheSurface) {
    const SurfaceBake holes = quadrants({Rgb(0.5), Rgb(0.5), Rgb(0.5), Rgb(0.5)}, {0.2f, 0.4f, 0.1f, 0.f});
    const Scene scene = planeScene();
    RenderOptions o = surfaceRender(holes);
    const RenderResult r = renderScene(scene, o);
    for (size_t i = 0; i < r.image.rgb.size(); ++i) EXPECT_NEAR(r.image.rgb[i], o.environment, 1e-6) << i;
    const SurfaceBake solid = quadrants({Rgb(0.5), Rgb(0.5), Rgb(0.5), Rgb(0.5)}, {0.6f, 0.6f, 0.6f, 0.6f});
    EXPECT_GT(renderScene(scene, surfaceRender(solid)).image.mean().g, 2 * o.environment);
}

// One bounce on a plane: the image is linear in the baked albedo (same seed, same paths).
TEST(SurfaceRender, radianceScalesWithTheBakedAlbedo) {
    const Scene scene = planeScene();
    const SurfaceBake dark = quadrants({Rgb(0.2), Rgb(0.2), Rgb(0.2), Rgb(0.2)}, {1, 1, 1, 1});
    const SurfaceBake bright = quadrants({Rgb(0.4), Rgb(0.4), Rgb(0.4), Rgb(0.4)}, {1, 1, 1, 1});
    RenderOptions o = surfaceRender(dark);
    o.environment = 0;
    const double a = renderScene(scene, o).image.mean().g;
    o.surface = &bright;
    const double b = renderScene(scene, o).image.mean().g;
    ASSERT_GT(a, 0);
    EXPECT_NEAR(b / a, 2.0, 1e-3);
}

// Back-lit, no environment: the side the camera sees is lit only through the surface, so the
// plane's pixels (the middle of the frame; the lightbox shows around it) are the baked
// transmittance's: black without it, linear in it (black albedo: every path transmits, the same
// paths for both).
TEST(SurfaceRender, backLightComesThroughTheBakedTransmittance) {
    const Scene scene = planeScene();
    SurfaceBake bake = quadrants({Rgb(0.0), Rgb(0.0), Rgb(0.0), Rgb(0.0)}, {1, 1, 1, 1});
    RenderOptions o = surfaceRender(bake);
    o.environment = 0;
    o.light = LightPlacement::Back;
    auto plane = [&] {
        const Image im = renderScene(scene, o).image;
        double g = 0;
        for (int y = 9; y <= 14; ++y)
            for (int x = 9; x <= 14; ++x) g += im.pixel(x, y).g;
        return g / 36;
    };
    EXPECT_EQ(plane(), 0.0) << "no transmittance baked: no light through";
    bake.transmittance.assign(12, 0.2f);
    const double a = plane();
    bake.transmittance.assign(12, 0.4f);
    const double b = plane();
    ASSERT_GT(a, 0);
    EXPECT_NEAR(b / a, 2.0, 1e-3);
}

// White furnace for the surface BSDF: under a uniform environment E alone, a plane that reflects
// a and transmits t sends (a + t) E towards the camera, whatever the split. (The environment is
// also sampled directly and weighted by MIS, so the estimate has noise: 256 paths per pixel.)
TEST(SurfaceRender, furnaceSendsBackTheReflectedPlusTheTransmittedLight) {
    const Scene scene = planeScene();
    auto plane = [&](double a, double t) {
        SurfaceBake bake = quadrants({Rgb(a), Rgb(a), Rgb(a), Rgb(a)}, {1, 1, 1, 1});
        bake.transmittance.assign(12, float(t));
        RenderOptions o = surfaceRender(bake);
        o.environment = 1, o.lightIrradiance = 0, o.spp = 256;
        const Image im = renderScene(scene, o).image;
        double g = 0;
        for (int y = 9; y <= 14; ++y)
            for (int x = 9; x <= 14; ++x) g += im.pixel(x, y).g;
        std::printf("furnace: albedo %.2f, transmittance %.2f: %.5f\n", a, t, g / 36);
        return g / 36;
    };
    EXPECT_NEAR(plane(0.6, 0.0), 0.6, 0.006);
    EXPECT_NEAR(plane(0.3, 0.3), 0.6, 0.006);
    EXPECT_NEAR(plane(0.1, 0.5), 0.6, 0.006);
    EXPECT_NEAR(plane(0.45, 0.2), 0.65, 0.0065);
}

}  // namespace
}  // namespace knit
