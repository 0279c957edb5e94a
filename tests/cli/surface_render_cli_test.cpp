// `knit render --surface-only`: the base mesh traced with the baked knit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "common/run_knit.hpp"

namespace fs = std::filesystem;

namespace {

TEST(SurfaceRenderCli, surfaceOnlyRendersTheBakedBaseMeshAndReportsTheBake) {
    const fs::path dir = fs::temp_directory_path() / ("knit_surface_render_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto r = knit::test::runKnit("render -q --surface-only --bake-size 16 --mesh-res 4 --repeats 4 4 --spp 1 "
                                       "--width 32 --height 24 --output s.png --report r.json",
                                       dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "s.png"));
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "r.json"));
    EXPECT_EQ(report["surface"]["bakeWidth"], 16);
    EXPECT_EQ(report["geometryMemoryBytes"], 0) << "no plies are traced at the surface level";
    fs::remove_all(dir);
}

}  // namespace
