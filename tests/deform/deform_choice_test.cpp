// The default deformation (knit::decideDeform, the one rule behind --deform, Python's deform= and
// Blender's Deform): strain where the pattern's table is at hand (given, cached, or quick to make),
// none with an estimate where making one takes minutes; and why that default is reproducible: a
// pattern's table is the same bytes made with any thread count and read back from the cache.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include <tbb/global_control.h>

#include "common/fixtures.hpp"
#include "test_util.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

// A small table (27 samples) so the test runs in a fraction of a second.
StrainTableOptions smallOptions() {
    StrainTableOptions o;
    o.samples = {3, 3, 3};
    return o;
}

// Sets KNIT_CACHE_DIR to a fresh folder for the test's lifetime.
struct TempCache {
    test::TempDir dir;
    std::string path = dir.file("cache");
    TempCache() { ::setenv("KNIT_CACHE_DIR", path.c_str(), 1); }
    ~TempCache() { ::unsetenv("KNIT_CACHE_DIR"); }
    size_t entries() const {
        size_t n = 0;
        std::error_code ec;
        if (std::filesystem::exists(path, ec))
            for (const auto& e : std::filesystem::directory_iterator(path)) n += e.path().extension() == ".npy";
        return n;
    }
};

TEST(DeformChoice, aTableIsTheSameBytesWithAnyThreadCountAndFromTheCache) {
    const test::TempDir dir;
    const Pattern p = generateStockinette();
    StrainTable one, many;
    {
        const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = makeStrainTable(p, smallOptions());
    }
    many = makeStrainTable(p, smallOptions());
    std::filesystem::create_directories(dir.file("one"));
    std::filesystem::create_directories(dir.file("many"));
    writeStrainTable(one, dir.file("one/t.npy"));
    writeStrainTable(many, dir.file("many/t.npy"));
    EXPECT_EQ(test::readText(dir.file("one/t.npy")), test::readText(dir.file("many/t.npy")));
    EXPECT_EQ(test::readText(dir.file("one/t.axes.txt")), test::readText(dir.file("many/t.axes.txt")));
    // Read back: the same numbers (float32 data, axes written with 17 digits), so a scene made
    // with the table just made and one made with the cached file are the same bits.
    auto loaded = std::make_shared<const StrainTable>(loadStrainTable(dir.file("many/t.npy")));
    EXPECT_EQ(loaded->data, many.data);
    EXPECT_EQ(loaded->axes, many.axes);
    EXPECT_EQ(loaded->px, many.px);
    SceneOptions o;
    o.buildPlies = false;
    o.placement.repeats = {0.05 / (1.3 * p.px), 0.05 / p.py};  // stretched along the courses: the table acts
    o.deform.mode = DeformMode::Strain;
    o.deform.table = std::make_shared<const StrainTable>(std::move(many));
    const Scene made = buildScene(p, test::planeMesh(test::Triangulation::Regular, 8, 0.05), o);
    o.deform.table = loaded;
    const Scene read = buildScene(p, test::planeMesh(test::Triangulation::Regular, 8, 0.05), o);
    ASSERT_GT(made.deformStats().vertices, 0U);
    const auto& a = made.yarns().curves.points;
    const auto& b = read.yarns().curves.points;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])), 0);
}

TEST(DeformChoice, autoIsStrainWhereTheTableIsQuickOrCachedElseNoneWithAnEstimate) {
    const TempCache cache;
    const Pattern p = generateStockinette();  // 24 cell vertices: quick
    ASSERT_TRUE(strainTableIsQuick(p));
    int made = 0;
    const auto make = [&] {
        ++made;
        return makeStrainTable(p, smallOptions());
    };
    const DeformDecision first = decideDeform(p, DeformChoice::Auto, {}, make);
    EXPECT_EQ(first.deform.mode, DeformMode::Strain);
    EXPECT_EQ(first.deform.reason, DeformReason::Made);
    EXPECT_TRUE(first.cached.made);
    ASSERT_NE(first.deform.table, nullptr);
    EXPECT_EQ(cache.entries(), 1U);
    const DeformDecision second = decideDeform(p, DeformChoice::Auto, {}, make);
    EXPECT_EQ(second.deform.reason, DeformReason::Cached);
    EXPECT_EQ(made, 1);
    EXPECT_EQ(second.deform.table->data, first.deform.table->data);
    // Asked for: none stays none, a given table is used as it is.
    EXPECT_EQ(decideDeform(p, DeformChoice::None, first.deform.table).deform.mode, DeformMode::None);
    const DeformDecision given = decideDeform(p, DeformChoice::Auto, first.deform.table);
    EXPECT_EQ(given.deform.reason, DeformReason::TableGiven);
    EXPECT_EQ(given.deform.table, first.deform.table);

    // A pattern of 48 cell vertices: its 9 x 9 x 9 table would take minutes.
    StockinetteParams big;
    big.samplesPerStitch = 48;
    const Pattern slow = generateStockinette(big);
    ASSERT_FALSE(strainTableIsQuick(slow));
    const DeformDecision none = decideDeform(slow, DeformChoice::Auto, {}, make);
    EXPECT_EQ(none.deform.mode, DeformMode::None);
    EXPECT_EQ(none.deform.reason, DeformReason::TooSlowToMake);
    EXPECT_GT(none.deform.tableSeconds, 0.0);
    EXPECT_EQ(made, 1);  // nothing made, nothing cached
    EXPECT_EQ(cache.entries(), 1U);
    // Asking for strain makes it anyway; afterwards Auto finds it in the cache.
    const DeformDecision asked = decideDeform(slow, DeformChoice::Strain, {}, [&] {
        ++made;
        StrainTableOptions o = smallOptions();
        o.samples = {2, 1, 2};
        o.saRange = {0.0, 0.0};
        return makeStrainTable(slow, o);
    });
    EXPECT_EQ(asked.deform.mode, DeformMode::Strain);
    EXPECT_EQ(asked.deform.reason, DeformReason::Made);
    EXPECT_EQ(made, 2);
    EXPECT_EQ(decideDeform(slow, DeformChoice::Auto).deform.reason, DeformReason::Cached);
}

}  // namespace
}  // namespace knit
