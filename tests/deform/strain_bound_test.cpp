// The feasibility bound behind docs/deformation.md's targets (tools/strain_bound.cpp): a taut
// yarn (rest lengths below the pattern's, so it pulls itself as short as its crossings allow)
// on strained lattices, and the tables' option to relax a sample from several neighbours.
#include <gtest/gtest.h>

#include <string>

#include "test_util.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/strain.hpp"
#include "chart/relax_lattice.hpp"

namespace knit {
namespace {

// The stockinette's yarn relaxed taut on the lattice of `s` (tools/strain_bound's defaults: rest
// lengths 0.8 of the pattern's, stretch weight 200, no penalty, a barrier from `distance` radii).
StrainCellResult tautAt(const Strain& s, double distance, double restLengthScale = 0.8) {
    StrainTableOptions o;
    o.stretch = 200;
    o.contact = 0;
    o.contactDistance = distance;
    o.barrierDistance = distance;
    return relaxStrainCell(generateStockinette(), s, o, restLengthScale);
}

// Shortened rest lengths pull the yarn taut: at rest it gives up slack (the relaxed stockinette
// is not the shortest yarn its crossings allow) while the barrier keeps its crossings apart; with
// the pattern's own rest lengths the same relaxation keeps the length.
TEST(StrainBound, aTautYarnGivesUpTheRestCellsSlackButKeepsItsCrossings) {
    const StrainCellResult taut = tautAt({0, 0, 0}, 2.0), own = tautAt({0, 0, 0}, 2.0, 1.0);
    EXPECT_LT(taut.lengthRatio, 0.97);
    EXPECT_GT(taut.lengthRatio, 0.90);
    EXPECT_GT(taut.closestRadii, 1.8);
    EXPECT_NEAR(own.lengthRatio, 1.0, 0.01);
}

// The bound the docs state: with crossings pressed to about 1.1 radii a taut yarn needs no more
// than 5 % over its rest length at 50 % along the wales, but more than 10 % at 50 % in both
// directions: the biaxial target is out of reach of an inextensible yarn with this crossing
// structure, the uniaxial ones are not.
TEST(StrainBound, biaxialFiftyPercentNeedsMoreYarnThanTheTargetAllows) {
    const StrainCellResult wales = tautAt({0, 0, 0.5}, 1.25), biaxial = tautAt({0.5, 0, 0.5}, 1.25);
    EXPECT_LT(wales.lengthRatio, 1.05);
    EXPECT_GT(wales.closestRadii, 1.0);
    EXPECT_GT(biaxial.lengthRatio, 1.10);
    EXPECT_GT(biaxial.closestRadii, 1.0);
}

TEST(StrainBound, restLengthScaleMustBePositive) {
    impl::LatticeRelaxOptions o;
    o.restLengthScale = 0;
    EXPECT_NE(test::errorOf([&] { impl::LatticeCell(generateStockinette(), o); }).find("rest length scale"),
              std::string::npos);
}

// Several starts per sample: refused outside 1-3, naming the option; a table along one axis (every
// sample has one lower neighbour) is the same bytes with any count; the cache tells them apart.
TEST(StrainBound, startsPerSampleOnlyChangesSamplesWithSeveralLowerNeighbours) {
    StrainTableOptions o;
    o.samples = {3, 1, 1};
    o.sxRange = {0.0, 0.3};
    o.saRange = {0.0, 0.0};
    o.syRange = {0.0, 0.0};
    const Pattern p = generateStockinette();
    const StrainTable one = makeStrainTable(p, o);
    o.startsPerSample = 3;
    const StrainTable three = makeStrainTable(p, o);
    EXPECT_EQ(one.data, three.data);
    // On a 3 x 1 x 3 grid the samples off both axes have two lower neighbours: a second start
    // can settle them elsewhere (here it does); the samples on the axes (one neighbour) are unchanged.
    o.samples = {3, 1, 3};
    o.syRange = {0.0, 0.6};
    o.sxRange = {0.0, 0.6};
    o.startsPerSample = 1;
    const StrainTable grid1 = makeStrainTable(p, o);
    o.startsPerSample = 2;
    const StrainTable grid2 = makeStrainTable(p, o);
    size_t changed = 0, changedOnAxes = 0;
    for (size_t v = 0; v < grid1.vertexCount; ++v)
        for (size_t s = 0; s < grid1.samples(); ++s)
            for (size_t c = 0; c < 3; ++c) {
                const size_t at = 4 * (s + grid1.samples() * v) + c;
                if (grid1.data[at] == grid2.data[at]) continue;
                ++changed;
                changedOnAxes += (s % 3 == 0 || s / 3 == 0) ? 1 : 0;
            }
    EXPECT_GT(changed, 0U);
    EXPECT_EQ(changedOnAxes, 0U);
    const StrainTableOptions defaults;
    StrainTableOptions threeStarts;
    threeStarts.startsPerSample = 3;
    EXPECT_NE(strainCacheKey(p, defaults), strainCacheKey(p, threeStarts));
    o.startsPerSample = 4;
    EXPECT_NE(test::errorOf([&] { makeStrainTable(p, o); }).find("starts per sample"), std::string::npos);
}

}  // namespace
}  // namespace knit
