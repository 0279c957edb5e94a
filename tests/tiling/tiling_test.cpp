// Placement with a gauge: parsing, the repeats it gives, and its exclusion of the repeats.
#include <gtest/gtest.h>

#include <cmath>

#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/tiling.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

std::string gaugeError(const std::string& text) {
    return test::errorOf([&] { parseGauge(text); });
}

TEST(Gauge, parsesStitchesRowsAndLengthInEveryUnit) {
    const Gauge g = parseGauge("22x30/10cm");
    EXPECT_EQ(g.stitches, 22);
    EXPECT_EQ(g.rows, 30);
    EXPECT_DOUBLE_EQ(g.length, 0.1);
    EXPECT_DOUBLE_EQ(parseGauge(" 18 X 24 / 4 in").length, 4 * 0.0254);
    EXPECT_DOUBLE_EQ(parseGauge("5x7/25mm").length, 0.025);
    EXPECT_DOUBLE_EQ(parseGauge("220x300/1m").length, 1.0);
    EXPECT_DOUBLE_EQ(parseGauge("22.5x30/10cm").stitches, 22.5);
}

TEST(Gauge, malformedGaugesNameTheSettingAndWhatIsWrong) {
    EXPECT_NE(gaugeError("22x30").find("the gauge '22x30': no '/' before the length"), std::string::npos)
        << gaugeError("22x30");
    EXPECT_NE(gaugeError("22/10cm").find("no 'x' between stitches and rows"), std::string::npos);
    EXPECT_NE(gaugeError("22x30/10").find("the length has no unit"), std::string::npos);
    EXPECT_NE(gaugeError("22x30/10ft").find("unknown length unit 'ft'"), std::string::npos);
    EXPECT_NE(gaugeError("0x30/10cm").find("stitches '0' must be positive and finite"), std::string::npos);
    EXPECT_NE(gaugeError("22xabc/10cm").find("rows 'abc' is not a number"), std::string::npos);
    EXPECT_NE(gaugeError("22x30/cm").find("length '' is not a number"), std::string::npos);
    EXPECT_NE(gaugeError("22x30/-1cm").find("length '-1' must be positive"), std::string::npos);
    EXPECT_NE(gaugeError("").find("the gauge ''"), std::string::npos);
}

// The built-in plane is 0.5 m square; one period of the generated stockinette is one stitch by
// one row, so 22 x 30 stitches per 10 cm are 110 x 150 periods across it.
TEST(Gauge, twentyTwoByThirtyPerTenCmOnThePlaneGivesTheRepeats) {
    PlacementOptions o;
    o.gauge = parseGauge("22x30/10cm");
    const Pattern p = generateStockinette();
    const PatternPlacement pl = placePattern(p, makePlane(), o);
    EXPECT_NEAR(pl.repeats.x, 110.0, 1e-9);
    EXPECT_NEAR(pl.repeats.y, 150.0, 1e-9);
    EXPECT_NEAR(pl.periodMetres.x, 0.1 / 22, 1e-15);
    EXPECT_NEAR(pl.periodMetres.y, 0.1 / 30, 1e-15);
    EXPECT_NEAR(pl.scale, std::sqrt((0.1 / 22 / p.px) * (0.1 / 30 / p.py)), 1e-12);
}

// A chart-made pattern of 4 stitches by 6 rows per period repeats 4 and 6 times less often.
TEST(Gauge, aPatternWithSeveralStitchesPerPeriodRepeatsLessOften) {
    PlacementOptions o;
    o.gauge = parseGauge("22x30/10cm");
    Pattern p = generateStockinette();
    p.stitchesPerPeriod = 4;
    p.rowsPerPeriod = 6;
    const PatternPlacement pl = placePattern(p, makePlane(), o);
    EXPECT_NEAR(pl.repeats.x, 110.0 / 4, 1e-9);
    EXPECT_NEAR(pl.repeats.y, 150.0 / 6, 1e-9);
}

TEST(Gauge, gaugeWithRepeatsIsAnErrorNamingBoth) {
    PlacementOptions o;
    o.gauge = parseGauge("22x30/10cm");
    o.repeats = {4, 4};
    const std::string e = test::errorOf([&] { placePattern(generateStockinette(), makePlane(), o); });
    EXPECT_NE(e.find("the gauge and the repeats are mutually exclusive"), std::string::npos) << e;
}

// Without a gauge the placement is what it was: the same repeats and scale.
TEST(Gauge, noGaugeKeepsThePhysicalSize) {
    const Pattern p = generateStockinette();
    const BaseMesh plane = makePlane();
    const PatternPlacement pl = placePattern(p, plane, {});
    EXPECT_DOUBLE_EQ(pl.repeats.x, uvToMetreScale(plane).x / p.px);
    EXPECT_DOUBLE_EQ(pl.scale, 1.0);
}

}  // namespace
}  // namespace knit
