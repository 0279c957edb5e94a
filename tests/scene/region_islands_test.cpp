// A view's region build over overlapping UV islands: each island is stitched on its own, and the
// memory check of the yarns kept counts every island's yarns together (not one island at a time).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "knit/budget.hpp"
#include "knit/detail.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"
#include "scene/scene_budget.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

// Two 0.1 m quads side by side with the same UVs (0..1): two overlapping UV islands, both in view.
SceneOptions twoIslandView(const std::string& mesh) {
    SceneOptions so;
    so.mesh = mesh;
    so.placement.repeats = {3, 3};
    so.buildPlies = false;
    DetailOptions d;
    d.region = true;
    d.viewSettings.width = 640, d.viewSettings.height = 480;
    so.detail = d;
    return so;
}

TEST(RegionIslands, yarnBudgetCountsEveryIslandTogether) {
    test::TempDir dir;
    const std::string mesh = (dir.path() / "two.obj").string();
    std::ofstream(mesh) << "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\n"
                           "v 0.15 0 0\nv 0.25 0 0\nv 0.25 0.1 0\nv 0.15 0.1 0\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                           "f 1/1 2/2 3/3 4/4\nf 5/1 6/2 7/3 8/4\n";
    const Scene whole = buildScene(twoIslandView(mesh));
    ASSERT_EQ(whole.stages().islandTilings.size(), 2u);
    const UvYarns& kept = whole.stages().uvYarns;
    std::vector<uint64_t> perIsland(2, 0);
    for (size_t y = 0; y < kept.yarnCount(); ++y)
        perIsland.at(kept.island.at(y)) += kept.offsets[y + 1] - kept.offsets[y];
    ASSERT_GT(perIsland[0], 0u);
    ASSERT_GT(perIsland[1], 0u);
    const uint64_t total = perIsland[0] + perIsland[1];
    ASSERT_EQ(total, kept.vertexCount());
    // A budget each island's yarns fit in alone but not both together: refused, naming them.
    SceneOptions tight = twoIslandView(mesh);
    const double between =
        double(std::max(perIsland[0], perIsland[1])) + 0.5 * double(std::min(perIsland[0], perIsland[1]));
    tight.budget = MemoryBudget(uint64_t(between * impl::kBytesPerYarnVertex));
    try {
        buildScene(tight);
        ADD_FAILURE() << "both islands' " << total << " yarn vertices were accepted under a budget for " << between;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("yarn vertices through the view"), std::string::npos) << e.what();
    }
    // A budget all of them fit in: built.
    SceneOptions enough = twoIslandView(mesh);
    enough.budget = MemoryBudget(uint64_t(double(total) * impl::kBytesPerYarnVertex * 1.01) + 1);
    EXPECT_NO_THROW(buildScene(enough));
}

}  // namespace
}  // namespace knit
