// The render flags of `knit render` (apps/knit/render_flags.cpp): words to enums and material
// overrides resolved by the render check.
#include <gtest/gtest.h>

#ifdef KNIT_HAVE_RENDER_CHECK
#include <iterator>

#include <CLI/CLI.hpp>

#include "knit/error.hpp"
#include "render_flags.hpp"

namespace knit::cli {
namespace {

TEST(RenderFlags, flagsFillOptionsAndMaterialOverrides) {
    CLI::App app("render");
    RenderOptions o;
    addRenderFlags(app, o);
    const char* argv[] = {"knit",   "--light", "back",        "--mode",        "grid", "--spp",
                          "4",      "--kR",    "0.2,0.3,0.4", "--body-albedo", "0.5",  "--no-fiber-detail",
                          "--seed", "9"};
    app.parse(static_cast<int>(std::size(argv)), argv);
    EXPECT_EQ(o.light, LightPlacement::Back);
    EXPECT_EQ(o.mode, GeometryMode::Grid);
    EXPECT_EQ(o.spp, 4);
    EXPECT_EQ(o.seed, 9u);
    const PlyMaterial m = resolveMaterial(o);
    EXPECT_EQ(m.kR, Rgb(0.2, 0.3, 0.4));
    EXPECT_EQ(m.bodyAlbedo, Rgb(0.5));
    EXPECT_FALSE(m.fiberDetail);
    // An energy-violating flag combination is refused when resolved.
    CLI::App app2("render");
    RenderOptions bad;
    addRenderFlags(app2, bad);
    const char* argv2[] = {"knit", "--kTT", "0.7", "--body-albedo", "0.4"};
    app2.parse(static_cast<int>(std::size(argv2)), argv2);
    EXPECT_THROW(resolveMaterial(bad), Error);
    CLI::App app3("render");
    RenderOptions o3;
    addRenderFlags(app3, o3);
    const char* argv3[] = {"knit", "--mode", "voxels"};
    EXPECT_THROW(app3.parse(static_cast<int>(std::size(argv3)), argv3), CLI::ValidationError);
}

TEST(RenderFlags, lightAndModeAcceptOnlyTheListedSpelling) {
    for (const char* word : {"BACK", "side"}) {
        CLI::App app("render");
        RenderOptions o;
        addRenderFlags(app, o);
        const char* argv[] = {"knit", "--light", word};
        EXPECT_THROW(app.parse(static_cast<int>(std::size(argv)), argv), CLI::ValidationError) << word;
        EXPECT_EQ(o.light, LightPlacement::Front) << word;
    }
    CLI::App app("render");
    RenderOptions o;
    addRenderFlags(app, o);
    const char* argv[] = {"knit", "--mode", "tubes", "--light", "front"};
    app.parse(static_cast<int>(std::size(argv)), argv);
    EXPECT_EQ(o.mode, GeometryMode::Tubes);
    EXPECT_EQ(o.light, LightPlacement::Front);
}

}  // namespace
}  // namespace knit::cli
#endif  // KNIT_HAVE_RENDER_CHECK
