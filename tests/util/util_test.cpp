// Tests for the internal utility layer (libknit/src/util): CSR offsets, the perpendicular
// helper, file extensions, finiteness checks, the constants and the /proc readers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "util/checks.hpp"
#include "util/csr.hpp"
#include "util/math.hpp"
#include "util/platform.hpp"

namespace knit::util {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- validOffsets / offsetEnds ---------------------------------------------------------------

TEST(ValidOffsets, emptyArrayIsNotEvenZeroRows) {
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{}, 0, 0));
    EXPECT_FALSE(offsetEnds(std::vector<uint32_t>{}, 0, 0));
    EXPECT_TRUE(validOffsets(std::vector<uint32_t>{0}, 0, 0));  // zero rows: the single 0
}

TEST(ValidOffsets, emptyRowsInTheMiddleAreValid) {
    EXPECT_TRUE(validOffsets(std::vector<uint32_t>{0, 2, 2, 2, 5}, 4, 5));
    EXPECT_TRUE(validOffsets(std::vector<size_t>{0, 0}, 1, 0));
}

TEST(ValidOffsets, unsortedOffsetsAreRejectedButKeepTheirEnds) {
    const std::vector<uint32_t> o{0, 3, 2, 5};
    EXPECT_FALSE(validOffsets(o, 3, 5));
    EXPECT_TRUE(offsetEnds(o, 3, 5));  // the caller names the first decreasing row itself
}

TEST(ValidOffsets, wrongEndStartOrRowCountIsRejected) {
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{0, 2, 4}, 2, 5));  // ends short of the items
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{0, 2, 6}, 2, 5));  // ends past the items
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{1, 2, 5}, 2, 5));  // does not start at 0
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{0, 2, 5}, 3, 5));  // one row missing
    EXPECT_FALSE(validOffsets(std::vector<uint32_t>{0, 2, 5}, 1, 5));  // one row too many
    EXPECT_TRUE(validOffsets(std::vector<uint32_t>{0, 2, 5}, 2, 5));
}

// ---- anyPerpendicular ------------------------------------------------------------------------

void expectUnitPerpendicular(const glm::dvec3& t, const glm::dvec3& p) {
    EXPECT_NEAR(glm::length(p), 1.0, 1e-15) << t.x << " " << t.y << " " << t.z;
    EXPECT_NEAR(glm::dot(p, t), 0.0, 1e-15) << t.x << " " << t.y << " " << t.z;
}

TEST(AnyPerpendicular, eachAxisGetsTheFirstOtherAxis) {
    EXPECT_EQ(anyPerpendicular(glm::dvec3(1, 0, 0)), glm::dvec3(0, 1, 0));
    EXPECT_EQ(anyPerpendicular(glm::dvec3(-1, 0, 0)), glm::dvec3(0, 1, 0));
    EXPECT_EQ(anyPerpendicular(glm::dvec3(0, 1, 0)), glm::dvec3(1, 0, 0));
    EXPECT_EQ(anyPerpendicular(glm::dvec3(0, -1, 0)), glm::dvec3(1, 0, 0));
    EXPECT_EQ(anyPerpendicular(glm::dvec3(0, 0, 1)), glm::dvec3(1, 0, 0));
    EXPECT_EQ(anyPerpendicular(glm::dvec3(0, 0, -1)), glm::dvec3(1, 0, 0));
}

TEST(AnyPerpendicular, tiesGoToXThenY) {
    // The least aligned axis is chosen with <=: equal components prefer x, then y.
    const double s3 = 1.0 / std::sqrt(3.0), s2 = 1.0 / std::sqrt(2.0), s6 = 1.0 / std::sqrt(6.0);
    const glm::dvec3 all(s3, s3, s3);  // x, y, z tie
    const glm::dvec3 expectAll = glm::normalize(glm::dvec3(1, 0, 0) - s3 * all);
    EXPECT_NEAR(glm::length(anyPerpendicular(all) - expectAll), 0.0, 1e-15);
    const glm::dvec3 yz(2 * s6, s6, s6);  // y, z tie below x: y
    EXPECT_GT(anyPerpendicular(yz).y, 0.9);
    const glm::dvec3 xy(s6, -s6, 2 * s6);  // x, y tie below z: x
    EXPECT_GT(anyPerpendicular(xy).x, 0.9);
    EXPECT_EQ(anyPerpendicular(glm::dvec3(s2, s2, 0)), glm::dvec3(0, 0, 1));  // z alone least aligned
    for (const glm::dvec3& t : {all, yz, xy}) expectUnitPerpendicular(t, anyPerpendicular(t));
}

TEST(AnyPerpendicular, resultIsUnitAndPerpendicularForRandomDirections) {
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    for (int k = 0; k < 1000; ++k) {
        const glm::dvec3 t = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
        expectUnitPerpendicular(t, anyPerpendicular(t));
    }
}

// ---- lowerExtension --------------------------------------------------------------------------

TEST(LowerExtension, upperCaseExtensionIsLoweredWithoutTheDot) {
    EXPECT_EQ(lowerExtension("A.GLB"), "glb");
    EXPECT_EQ(lowerExtension("out/Mesh.Obj"), "obj");
    EXPECT_EQ(lowerExtension("archive.tar.GZ"), "gz");  // only the last extension
}

TEST(LowerExtension, noExtensionGivesEmpty) {
    EXPECT_EQ(lowerExtension("mesh"), "");
    EXPECT_EQ(lowerExtension(""), "");
    EXPECT_EQ(lowerExtension("name."), "");  // a trailing dot names no extension either
}

TEST(LowerExtension, dotfileHasNoExtension) {
    EXPECT_EQ(lowerExtension(".bashrc"), "");
    EXPECT_EQ(lowerExtension("dir/.hidden"), "");
    EXPECT_EQ(lowerExtension(".hidden.PLY"), "ply");
}

TEST(LowerExtension, dotInFolderNameIsNotTheExtension) {
    EXPECT_EQ(lowerExtension("my.meshes/plane"), "");
    EXPECT_EQ(lowerExtension("my.meshes/plane.OFF"), "off");
    EXPECT_EQ(lowerExtension("./plane"), "");
}

// ---- finite / finiteUnit / positiveFinite ----------------------------------------------------

TEST(Finite, nanOrInfinityInAnyComponentFails) {
    EXPECT_TRUE(finite(0.0));
    EXPECT_TRUE(finite(glm::dvec3(1e308, -1e308, 0)));
    for (const double bad : {kNaN, kInf, -kInf}) {
        EXPECT_FALSE(finite(bad));
        EXPECT_FALSE(finite(glm::dvec2(bad, 0)));
        EXPECT_FALSE(finite(glm::dvec2(0, bad)));
        EXPECT_FALSE(finite(glm::dvec3(bad, 0, 0)));
        EXPECT_FALSE(finite(glm::dvec3(0, bad, 0)));
        EXPECT_FALSE(finite(glm::dvec3(0, 0, bad)));
        EXPECT_FALSE(finite(glm::vec3(0, 0, float(bad))));
    }
}

TEST(FiniteUnit, nanInfinityAndNonUnitLengthsFail) {
    EXPECT_TRUE(finiteUnit(glm::dvec3(0, 0, -1)));
    EXPECT_TRUE(finiteUnit(glm::dvec3(1 + 1e-8, 0, 0)));  // within the default 1e-6 on |v|^2
    EXPECT_FALSE(finiteUnit(glm::dvec3(1 + 1e-8, 0, 0), 1e-12));
    EXPECT_FALSE(finiteUnit(glm::dvec3(0, 0, 0)));
    EXPECT_FALSE(finiteUnit(glm::dvec3(2, 0, 0)));
    EXPECT_FALSE(finiteUnit(glm::dvec3(kNaN, 0, 0)));
    EXPECT_FALSE(finiteUnit(glm::dvec3(kInf, 0, 0)));
    EXPECT_FALSE(finiteUnit(glm::dvec3(1e200, 1e200, 0)));  // |v|^2 overflows
}

TEST(PositiveFinite, zeroNegativeNanAndInfinityFail) {
    EXPECT_TRUE(positiveFinite(1e-300));
    for (const double bad : {0.0, -0.0, -1.0, kNaN, kInf, -kInf}) EXPECT_FALSE(positiveFinite(bad)) << bad;
    EXPECT_TRUE(positiveFinite(glm::dvec2(1, 2)));
    EXPECT_FALSE(positiveFinite(glm::dvec2(1, 0)));
    EXPECT_FALSE(positiveFinite(glm::dvec2(kNaN, 1)));
}

// ---- constants and the process readers --------------------------------------------------------

TEST(Constants, piMatchesTheLiteralsTheCodeUsedBefore) {
    EXPECT_EQ(kPi, 3.14159265358979323846);
    EXPECT_EQ(kPi, std::acos(-1.0));
    EXPECT_EQ(kTwoPi, 2.0 * kPi);
    EXPECT_EQ(float(kPi), 3.14159265f);
}

TEST(Platform, peakResidentIsAtLeastTheCurrentResident) {
    const size_t now = residentBytes();
    const size_t peak = peakResidentBytes();
    if (now == 0) GTEST_SKIP() << "no /proc/self/status";
    EXPECT_GE(peak, now);
}

}  // namespace
}  // namespace knit::util
