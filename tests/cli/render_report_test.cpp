// The JSON of `knit render` (apps/knit/render_report.cpp): settings, times, memory and the
// resolved material.
#include <gtest/gtest.h>

#ifdef KNIT_HAVE_RENDER_CHECK
#include "render_report.hpp"

namespace knit::cli {
namespace {

TEST(RenderReport, carriesSettingsTimesMemoryAndTheMaterial) {
    RenderResult r;
    r.image.width = 1;
    r.image.height = 1;
    r.image.rgb = {0.25f, 0.5f, 1.0f};
    r.mode = GeometryMode::Grid;
    r.light = LightPlacement::Back;
    r.spp = 4;
    r.tableSeconds = 1, r.buildSeconds = 2, r.renderSeconds = 4;
    r.rays = 100;
    r.memory.embreeBytes = 10, r.memory.geometryBytes = 5;
    r.material.fiberCount = 12;
    r.material.kR = Rgb(0.1, 0.2, 0.3);
    r.written = {"o.png"};
    const nlohmann::json j = renderReport(r);
    EXPECT_EQ(j["mode"], "grid");
    EXPECT_EQ(j["light"], "back");
    EXPECT_EQ(j["spp"], 4);
    EXPECT_DOUBLE_EQ(j["seconds"].get<double>(), 7.0);
    EXPECT_EQ(j["sceneMemoryBytes"], 15);
    EXPECT_EQ(j["meanRadiance"], nlohmann::json::parse("[0.25, 0.5, 1.0]"));
    EXPECT_EQ(j["material"]["fiberCount"], 12);
    EXPECT_EQ(j["material"]["kR"], nlohmann::json::parse("[0.1, 0.2, 0.3]"));
    EXPECT_EQ(j["material"].size(), 15u);  // every field of PlyMaterial
    EXPECT_EQ(j["written"], nlohmann::json::parse(R"(["o.png"])"));
}

}  // namespace
}  // namespace knit::cli
#endif  // KNIT_HAVE_RENDER_CHECK
