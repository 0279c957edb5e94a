#include <gtest/gtest.h>

#include "common/fixtures.hpp"
#include "test_util.hpp"
#include "knit/error.hpp"
#include "knit/uv_grid.hpp"

namespace knit {
namespace {

UvGrid gridFor(const BaseMesh& m, double cell) {
    UvGridOptions o;
    o.cellSize = glm::dvec2(cell);
    return buildUvGrid(m, o);
}

TEST(UvGrid, pointOnSharedEdgeAssignedOnce) {
    const BaseMesh m = test::planeMesh(test::Triangulation::Regular, 4);
    const UvGrid g = gridFor(m, 0.3);
    // Regular grid: quad (i, j) = faces 2*(4j+i) {a,b,c} and +1 {a,c,d}; its diagonal is shared.
    const glm::dvec2 onDiagonal(0.25 + 0.125, 0.25 + 0.125);  // quad (1,1) diagonal midpoint
    const LocateResult r = locatePoint(m, g, onDiagonal, 0);
    ASSERT_EQ(r.status, LocateStatus::Inside);
    EXPECT_EQ(r.point.face, 2u * (4 + 1));  // the lower-numbered of the two faces sharing it
    // A mesh vertex shared by six triangles goes to the lowest-numbered one.
    const LocateResult v = locatePoint(m, g, {0.5, 0.5}, 0);
    ASSERT_EQ(v.status, LocateStatus::Inside);
    EXPECT_EQ(v.point.face, 2u * (4 * 1 + 1));
    EXPECT_NEAR(glm::distance(v.point.interpolate(m.uvs, m.faceUvs), glm::dvec2(0.5, 0.5)), 0, 1e-15);
}

TEST(UvGrid, cellBoundaryPointsFindTheirTriangle) {
    // Cell size that does not divide the UV range evenly; points exactly on cell borders.
    const BaseMesh m = test::planeMesh(test::Triangulation::Random, 7);
    const UvGrid g = gridFor(m, 0.1);
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j) {
            const glm::dvec2 uv(i * 0.1, j * 0.1);
            if (uv.x > 1 || uv.y > 1) continue;
            const LocateResult r = locatePoint(m, g, uv, 0);
            ASSERT_EQ(r.status, LocateStatus::Inside) << uv.x << " " << uv.y;
            EXPECT_NEAR(glm::distance(r.point.interpolate(m.uvs, m.faceUvs), uv), 0, 1e-14);
        }
}

TEST(UvGrid, zeroAreaUvTriangleNeverOwnsAPoint) {
    BaseMesh m = test::planeMesh(test::Triangulation::Regular, 2);
    // Collapse face 0's uv triangle onto a line by adding a degenerate face with its own uvs.
    const uint32_t base = uint32_t(m.uvs.size());
    m.uvs.push_back({0.1, 0.1});
    m.uvs.push_back({0.2, 0.2});
    m.uvs.push_back({0.3, 0.3});
    m.faces.push_back({0, 1, 2});
    m.faceUvs.push_back({base, base + 1, base + 2});
    const UvGrid g = gridFor(m, 0.25);
    EXPECT_EQ(g.degenerateUvFaces, 1u);
    const LocateResult r = locatePoint(m, g, {0.2, 0.2}, 0);
    ASSERT_EQ(r.status, LocateStatus::Inside);
    EXPECT_NE(r.point.face, uint32_t(m.faces.size() - 1));
}

TEST(UvGrid, mirroredChartLocatesPoints) {
    BaseMesh m = test::planeMesh(test::Triangulation::Regular, 3);
    for (glm::dvec2& uv : m.uvs) uv.x = -uv.x;  // mirrored: clockwise triangles
    const UvGrid g = gridFor(m, 0.2);
    EXPECT_EQ(g.faceOrientation[0], -1);
    const LocateResult r = locatePoint(m, g, {-0.4, 0.7}, 0);
    ASSERT_EQ(r.status, LocateStatus::Inside);
    EXPECT_NEAR(glm::distance(r.point.interpolate(m.uvs, m.faceUvs), glm::dvec2(-0.4, 0.7)), 0, 1e-14);
}

TEST(UvGrid, pointJustOutsideIsClampedAndFarPointIsCut) {
    const BaseMesh m = test::planeMesh(test::Triangulation::Regular, 4);
    const UvGrid g = gridFor(m, 0.25);
    const LocateResult near = locatePoint(m, g, {1.0 + 1e-7, 0.3}, 1e-6);
    ASSERT_EQ(near.status, LocateStatus::Clamped);
    EXPECT_NEAR(near.distance, 1e-7, 1e-12);
    EXPECT_NEAR(near.point.interpolate(m.uvs, m.faceUvs).x, 1.0, 1e-15);
    EXPECT_EQ(locatePoint(m, g, {1.0 + 1e-5, 0.3}, 1e-6).status, LocateStatus::Outside);
    EXPECT_EQ(locatePoint(m, g, {-3, 7}, 1e-6).status, LocateStatus::Outside);
    EXPECT_EQ(locatePoint(m, g, {NAN, 0.5}, 1e-6).status, LocateStatus::Outside);
}

TEST(UvGrid, gridIsSparseAndConservative) {
    // Two small islands far apart: only the cells they touch exist, and every triangle is
    // listed in every cell its UV triangle touches (checked by sampling points).
    BaseMesh m = test::planeMesh(test::Triangulation::Random, 5);
    const size_t nuv = m.uvs.size();
    for (size_t i = 0; i < nuv; ++i) m.uvs[i] *= 0.05;
    BaseMesh far = m;
    for (glm::dvec2& uv : far.uvs) uv += glm::dvec2(0.9, 0.9);
    for (const glm::uvec3& f : far.faceUvs) m.faceUvs.push_back(f + glm::uvec3(uint32_t(nuv)));
    for (const glm::uvec3& f : far.faces) m.faces.push_back(f + glm::uvec3(uint32_t(m.positions.size())));
    m.uvs.insert(m.uvs.end(), far.uvs.begin(), far.uvs.end());
    m.positions.insert(m.positions.end(), far.positions.begin(), far.positions.end());
    const UvGrid g = gridFor(m, 0.01);
    // 0.05 / 0.01 = 5 cells per side, +1 where the far border touches the next cell.
    EXPECT_LE(g.cells.size(), 2u * 36u);
    EXPECT_EQ(g.islandOfFace.front() == g.islandOfFace.back(), false);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 20; ++k) {
            double a = u(rng), b = u(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const glm::uvec3 t = m.faceUvs[f];
            const glm::dvec2 p = m.uvs[t.x] + a * (m.uvs[t.y] - m.uvs[t.x]) + b * (m.uvs[t.z] - m.uvs[t.x]);
            const int32_t slot = g.slotOf(g.cellOf(p));
            ASSERT_GE(slot, 0);
            const auto begin = g.triangles.begin() + g.triOffsets[slot],
                       end = g.triangles.begin() + g.triOffsets[slot + 1];
            ASSERT_NE(std::find(begin, end, uint32_t(f)), end) << "face " << f << " missing from its cell";
        }
}

// Charts are numbered in the order of their lowest face, and pairs whose UV triangles overlap are
// reported exactly: sharing an edge or a corner is not an overlap, a sliver of overlap is.
TEST(UvGrid, overlappingChartsAreReportedTouchingOnesAreNot) {
    // Unit square a (two triangles) and a copy b of it moved by `shift` in UV (own UV vertices,
    // so a separate island); positions far apart so only UV relations matter.
    auto twoSquares = [](glm::dvec2 shift, double scaleB = 1.0) {
        BaseMesh m;
        m.name = "two-squares";
        for (int k = 0; k < 2; ++k) {
            const uint32_t p0 = uint32_t(m.positions.size()), t0 = uint32_t(m.uvs.size());
            for (const glm::dvec2 c : {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1)}) {
                m.positions.emplace_back(c.x, c.y, 5.0 * k);
                m.uvs.push_back(k == 0 ? c : shift + scaleB * c);
            }
            m.faces.emplace_back(p0, p0 + 1, p0 + 2);
            m.faces.emplace_back(p0, p0 + 2, p0 + 3);
            m.faceUvs.emplace_back(t0, t0 + 1, t0 + 2);
            m.faceUvs.emplace_back(t0, t0 + 2, t0 + 3);
        }
        return m;
    };
    struct Case {
        glm::dvec2 shift;
        double scale;
        bool overlap;
        const char* what;
    };
    const Case cases[] = {
        {{1, 0}, 1, false, "sharing an edge"},
        {{1, 1}, 1, false, "sharing a corner"},
        {{3, 0}, 1, false, "apart"},
        {{1 - 1e-12, 0}, 1, true, "a 1e-12 sliver"},
        {{0, 0}, 1, true, "stacked"},
        {{0.25, 0.25}, 0.5, true, "one inside the other"},
        {{1, 0.5}, 1, false, "edge contact, shifted"},
    };
    for (const Case& c : cases) {
        const UvGrid g = gridFor(twoSquares(c.shift, c.scale), 0.25);
        EXPECT_EQ(g.islandCount, 2u) << c.what;
        EXPECT_EQ(g.islandOfFace, (std::vector<uint32_t>{0, 0, 1, 1})) << c.what;
        if (c.overlap) {
            ASSERT_EQ(g.overlappingIslands.size(), 1u) << c.what;
            EXPECT_EQ(g.overlappingIslands[0], glm::uvec2(0, 1)) << c.what;
        } else {
            EXPECT_TRUE(g.overlappingIslands.empty()) << c.what;
        }
    }
    // One island only (a plane): nothing to compare.
    const UvGrid one = gridFor(test::planeMesh(test::Triangulation::Random, 6), 0.1);
    EXPECT_EQ(one.islandCount, 1u);
    EXPECT_TRUE(one.overlappingIslands.empty());
}

// Thousands of tiny islands stacked on one spot: every one is reported as overlapping (in some
// pair), with at most one pair per island.
TEST(UvGrid, crowdedOverlappingChartsAreAllFound) {
    BaseMesh m;
    m.name = "crowd";
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
        const uint32_t p = uint32_t(m.positions.size()), t = uint32_t(m.uvs.size());
        m.positions.insert(m.positions.end(), {{0.0, 0.0, 0.01 * k}, {1.0, 0.0, 0.01 * k}, {0.0, 1.0, 0.01 * k}});
        const double s = 1e-3 * (k % 7);  // slightly different, all overlapping near (0.1, 0.1)
        m.uvs.insert(m.uvs.end(), {{0.1 + s, 0.1}, {0.3, 0.1 + s}, {0.1, 0.3}});
        m.faces.emplace_back(p, p + 1, p + 2);
        m.faceUvs.emplace_back(t, t + 1, t + 2);
    }
    const UvGrid g = gridFor(m, 0.5);
    EXPECT_EQ(g.islandCount, uint32_t(n));
    EXPECT_LE(g.overlappingIslands.size(), size_t(n));
    std::vector<char> seen(n, 0);
    for (const glm::uvec2& pr : g.overlappingIslands) seen[pr.x] = seen[pr.y] = 1;
    for (int k = 0; k < n; ++k) EXPECT_TRUE(seen[size_t(k)]) << "island " << k;
}

TEST(UvGrid, absurdRepeatsAreRefused) {
    const BaseMesh m = test::planeMesh(test::Triangulation::Regular, 2);
    UvGridOptions o;
    o.cellSize = glm::dvec2(1e-6);
    EXPECT_THROW(buildUvGrid(m, o), Error);
}

// Found by the OFF fuzzer: a 40 KB file of big UV triangles stacked on each other asked for
// 10^8 (cell, triangle) entries (gigabytes, minutes) while its cell count was harmless.
TEST(UvGrid, stackedHugeTrianglesAreRefusedBeforeListingThem) {
    BaseMesh m;
    m.name = "stacked.off";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    for (int k = 0; k < 1000; ++k) {
        m.faces.push_back({0, 1, 2});
        m.faceUvs.push_back({0, 1, 2});
    }
    // 100 x 100 cells per triangle's box: the bound counts every face's box.
    EXPECT_EQ(uvGridEntryBound(m, glm::dvec2(0.01 + 1e-12)), 1000u * 100u * 100u);
    UvGridOptions o;
    o.cellSize = glm::dvec2(0.01 + 1e-12);
    o.maxEntries = 1000u * 100u * 100u - 1;
    try {
        buildUvGrid(m, o);
        FAIL() << "expected a refusal";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("stacked.off"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("10000000"), std::string::npos) << e.what();
    }
    o.maxEntries = 1000u * 100u * 100u;  // at the bound it is built, each face in its ~half of the box
    const UvGrid g = buildUvGrid(m, o);
    EXPECT_GT(g.triangles.size(), 1000u * 100u * 50u);
    EXPECT_LE(g.triangles.size(), 1000u * 100u * 100u);
}

// A zero-area UV triangle is never listed, so it adds nothing to the bound.
TEST(UvGrid, entryBoundSkipsZeroAreaTriangles) {
    BaseMesh m = test::planeMesh(test::Triangulation::Regular, 2);
    const uint64_t before = uvGridEntryBound(m, glm::dvec2(0.25));
    const uint32_t base = uint32_t(m.uvs.size());
    m.uvs.push_back({0.0, 0.0});
    m.uvs.push_back({0.5, 0.5});
    m.uvs.push_back({1.0, 1.0});
    m.faces.push_back({0, 1, 2});
    m.faceUvs.push_back({base, base + 1, base + 2});
    EXPECT_EQ(uvGridEntryBound(m, glm::dvec2(0.25)), before);
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

// The 8 x 8 plane with its UVs folded back at u = 0.75: the last two columns are mirrored onto
// the two before them (u -> 1.5 - u), so the island covers [0.5, 0.75] twice.
BaseMesh planeFoldedAtThreeQuarters() {
    BaseMesh m = test::planeMesh(test::Triangulation::Regular, 8);
    for (glm::dvec2& uv : m.uvs)
        if (uv.x > 0.75) uv.x = 1.5 - uv.x;
    return m;
}

TEST(UvGrid, chartFoldedOverItselfReportsItsSmallerSide) {
    const UvGrid g = gridFor(planeFoldedAtThreeQuarters(), 0.1);
    EXPECT_EQ(g.islandCount, 1u);
    EXPECT_EQ(g.foldedUvFaces, 2u * 8 * 2);    // two columns of 8 quads
    EXPECT_EQ(g.foldedUvFaceExample, 2u * 6);  // quad (6, 0), the first beyond the fold
}

TEST(UvGrid, windingAndMirroringAreNoFold) {
    // Every third face wound the other way (3D and UV alike), a whole island mirrored, a random
    // triangulation: the same UV region once each, so no fold.
    BaseMesh rewound = test::planeMesh(test::Triangulation::Regular, 8);
    for (size_t f = 0; f < rewound.faces.size(); f += 3) {
        std::swap(rewound.faces[f].y, rewound.faces[f].z);
        std::swap(rewound.faceUvs[f].y, rewound.faceUvs[f].z);
    }
    BaseMesh mirrored = test::planeMesh(test::Triangulation::Regular, 8);
    for (glm::dvec2& uv : mirrored.uvs) uv.x = 1 - uv.x;
    for (const BaseMesh& m : {rewound, mirrored, test::planeMesh(test::Triangulation::Random, 8)}) {
        const UvGrid g = gridFor(m, 0.1);
        EXPECT_EQ(g.foldedUvFaces, 0u);
        EXPECT_EQ(g.foldedUvFaceExample, UINT32_MAX);
    }
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

// Thousands of copies of a triangle spanning the whole UV range (a 40 KB OFF file): each touches
// ~30000 cells, so the triangle-cell lists would need gigabytes. Refused before allocating.
TEST(UvGrid, manyTrianglesSpanningTheWholeUvRangeAreRefusedBeforeAllocating) {
    BaseMesh m;
    m.name = "big-triangles.off";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {31.9, 0}, {0, 31.9}};  // 256 x 256 cells of 1/8
    m.faces.assign(5000, glm::uvec3(0, 1, 2));
    m.faceUvs = m.faces;
    UvGridOptions o;
    o.cellSize = glm::dvec2(1.0 / 8);
    o.maxCells = 1 << 16;
    const std::string e = test::errorOf([&] { buildUvGrid(m, o); });
    EXPECT_NE(e.find("big-triangles.off: its UV triangles would be listed in up to 327680000 pattern cells"),
              std::string::npos)
        << e;
    m.faces.resize(10);  // ten of them fit
    m.faceUvs = m.faces;
    EXPECT_GT(buildUvGrid(m, o).cells.size(), 30000u);
}

}  // namespace
}  // namespace knit
