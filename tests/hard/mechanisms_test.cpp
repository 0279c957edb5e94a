// Unit-level pins of the general mechanisms the hard-case catalogue needed (each also exercised
// end to end by a catalogue case): consistent winding for vertex normals, a UV-to-metre scale
// bounded under UV slivers, tiling within the clamp tolerance, and steps that leave their chart.
#include <gtest/gtest.h>

#include "catalogue.hpp"
#include "knit/tiling.hpp"

namespace knit::hard {
namespace {

TEST(Mechanisms, vertexNormalsOfInconsistentlyWoundMeshEqualTheConsistentOnes) {
    const BaseMesh clean = makeDrape({});
    const std::vector<glm::dvec3> expected = vertexNormals(clean.positions, clean.faces);
    BaseMesh flipped = clean;
    for (size_t f = 0; f < flipped.faces.size(); f += 3) std::swap(flipped.faces[f].y, flipped.faces[f].z);
    const std::vector<glm::dvec3> got = vertexNormals(flipped.positions, flipped.faces);
    double worst = 0;
    for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, glm::distance(got[i], expected[i]));
    EXPECT_LT(worst, 1e-12);
    // A whole mesh wound the other way keeps its own (reversed) normals: only relative winding
    // is corrected, the larger area decides the side.
    BaseMesh reversed = clean;
    for (glm::uvec3& f : reversed.faces) std::swap(f.y, f.z);
    const std::vector<glm::dvec3> back = vertexNormals(reversed.positions, reversed.faces);
    for (size_t i = 0; i < back.size(); ++i) ASSERT_LT(glm::distance(back[i], -expected[i]), 1e-12);
}

TEST(Mechanisms, uvToMetreScaleIsNotBlownUpByUvSlivers) {
    // A 0.1 m square whose UV has a column 1e-13 wide (3D width 1/8 of the square): metres per
    // unit u stays the mean 3D length of iso-v lines per UV unit (0.1 m over 0.875 UV).
    const BaseMesh m = sheet(
        "sliver", 8, 8, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.0); },
        [](double s, double t) { return glm::dvec2(s <= 0.5 ? s : (s < 0.6 ? 0.5 + 1e-13 : s - 1.0 / 8 + 1e-13), t); });
    // (Half of the sliver's triangles fall below the degenerate-UV threshold and are skipped,
    // so the result lies between the sliver ignored and the sliver counted in full.)
    const glm::dvec2 k = uvToMetreScale(m);
    EXPECT_GE(k.x, 0.0875 / 0.875 - 1e-9);
    EXPECT_LE(k.x, 0.1 / 0.875 + 1e-9);
    EXPECT_NEAR(k.y, 0.1, 1e-12);
}

TEST(Mechanisms, tilesForCellsMarginGeneratesTilesJustOutsideTheCells) {
    // Course at y = -1e-9: its tile j = 0 lands in cell row -1, which the mesh does not cover.
    const Pattern p = straightCourses(0.01, 0.01, 0.001, -1e-9, 2);
    const std::vector<glm::ivec2> cells = {{0, 0}};
    const Tiling plain = tilesForCells(p, cells);
    EXPECT_EQ(plain.slotOf({0, 0}), -1);
    EXPECT_GE(plain.slotOf({0, 1}), 0);
    const Tiling grown = tilesForCells(p, cells, glm::dvec2(1e-6));
    EXPECT_GE(grown.slotOf({0, 0}), 0);
    EXPECT_GE(grown.slotOf({0, 1}), 0);
    // Absurd margins are bounded by one period; NaN counts as none.
    EXPECT_LE(tilesForCells(p, cells, glm::dvec2(1e9)).tiles.size(), 9u);
    EXPECT_EQ(tilesForCells(p, cells, glm::dvec2(NAN)).tiles.size(), plain.tiles.size());
}

TEST(Mechanisms, stepOverAHoleInTheChartIsCut) {
    // A square chart with a square hole (4 x 4 quads of a 12 x 12 grid missing); straight courses
    // step over the hole in one step. Each course through the hole is cut at both sides.
    BaseMesh m = flatSquare(12, 0.12);
    BaseMesh holed = m;
    holed.faces.clear();
    holed.faceUvs.clear();
    for (size_t f = 0; f < m.faces.size(); ++f) {
        glm::dvec2 c(0.0);
        for (int k = 0; k < 3; ++k) c += m.uvs[m.faceUvs[f][k]] / 3.0;
        if (c.x > 4.0 / 12 && c.x < 8.0 / 12 && c.y > 4.0 / 12 && c.y < 8.0 / 12) continue;
        holed.faces.push_back(m.faces[f]);
        holed.faceUvs.push_back(m.faceUvs[f]);
    }
    // One vertex per period, at u = 0.25 and 0.75 with 2 repeats: one step over the hole.
    const Scene s = buildScene(straightCourses(0.01, 0.01, 0.0005, 0.005, 1, 0.005), holed, withRepeats(2, 12, false));
    size_t through = 0;  // courses at v in (1/3, 2/3)
    for (int j = 0; j < 12; ++j) through += (j + 0.5) / 12 > 4.0 / 12 && (j + 0.5) / 12 < 8.0 / 12;
    EXPECT_EQ(s.yarns().curves.curveCount(), 12 + through);
    for (const glm::dvec3& p : s.yarns().curves.points) {
        const glm::dvec2 uv = glm::dvec2(p) / 0.12;
        EXPECT_FALSE(uv.x > 4.0 / 12 + 1e-9 && uv.x < 8.0 / 12 - 1e-9 && uv.y > 4.0 / 12 && uv.y < 8.0 / 12)
            << "a yarn point in the hole";
    }
}

}  // namespace
}  // namespace knit::hard
