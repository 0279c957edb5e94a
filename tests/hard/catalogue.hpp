// catalogue.hpp — the curated hard cases (UV layouts, 3D geometry, curves). Each entry is a
// pattern, a mesh, scene options, the invariants' expectations and, where the case has a
// documented behaviour of its own, a check of it. catalogue_test.cpp runs every entry through
// the whole pipeline (one test per entry); docs/hard-cases.md explains each class.
#pragma once
#include <map>

#include "hard_cases.hpp"
#include "knit/uv_grid.hpp"

namespace knit::hard {

// Bound yarn vertices whose mapped point is (size*u, size*v, h) for a plane with uv = (x, y)/size
// (up to `mirror`ed u): the worst distance, relative to size.
inline double planeMappingError(const Scene& s, double size, glm::dvec2 uvOrigin = glm::dvec2(0.0),
                                bool mirror = false) {
    double worst = 0;
    const Binding& b = s.binding();
    for (size_t i = 0; i < b.vertexCount(); ++i) {
        const glm::dvec2 uv = boundUv(s, i) - uvOrigin;
        const glm::dvec3 expected((mirror ? -uv.x : uv.x) * size, uv.y * size, b.height[i]);
        worst = std::max(worst, glm::distance(s.yarns().curves.points[i], expected) / size);
    }
    return worst;
}

inline std::vector<HardCase> catalogue() {
    std::vector<HardCase> cases;
    const Pattern stockinette = generateStockinette();
    auto add = [&](std::string name, Pattern pattern, BaseMesh mesh, SceneOptions options, Expect expect = {},
                   std::function<void(const Scene&)> check = {}) {
        cases.push_back(
            {std::move(name), std::move(pattern), std::move(mesh), std::move(options), expect, std::move(check)});
    };

    // ======================= UV ==============================================================
    // Pattern vertices exactly on mesh vertices, shared edges and quad diagonals (8 x 8 regular
    // grid, one cell per quad). Every vertex inside the closed square is Inside (none clamped or
    // cut); exactly those outside it are cut; yarns along v = 0 and v = 1 run on the boundary.
    add("uvPointsOnSharedEdgesAndVertices", gridAlignedPattern(), flatSquare(8, 0.1), withRepeats(8, 8), {},
        [](const Scene& s) {
            size_t outside = 0;
            for (const glm::dvec2& uv : s.stages().uvYarns.uv) outside += uv.x < 0 || uv.x > 1 || uv.y < 0 || uv.y > 1;
            EXPECT_EQ(s.bindStats().cutVertices, outside);
            EXPECT_EQ(s.bindStats().clampedVertices, 0u);
            EXPECT_LT(planeMappingError(s, 0.1), 1e-12);
            // 9 courses at v = k/8 and 8 at v = (k + 1/2)/8, all open (a square, no seam).
            EXPECT_EQ(s.yarns().curves.curveCount(), 17u);
        });

    // Zero-area UV triangles: one column of the sheet collapsed in UV (its two UV columns share
    // UV vertices, so the chart stays connected) plus a triangle whose three UVs coincide. They
    // never own a point; a yarn steps over the collapsed column's 3D width in one segment.
    {
        const int n = 8;
        BaseMesh m = sheet(
            "zero-area-uv", n, n, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.0); },
            [](double s, double t) { return glm::dvec2(s <= 0.5 ? s : s - 1.0 / 8, t); });
        // Merge the UV vertices of column 5 into column 4 (same values): zero-width UV column.
        for (glm::uvec3& f : m.faceUvs)
            for (int k = 0; k < 3; ++k)
                if (f[k] % (n + 1) == 5) f[k] -= 1;
        const uint32_t p = uint32_t(m.positions.size());
        m.positions.push_back({0.05, 0.05, 0.01});
        m.uvs.push_back({0.3, 0.3});
        m.faces.push_back({p, 0, 1});
        m.faceUvs.push_back({uint32_t(m.uvs.size() - 1), uint32_t(m.uvs.size() - 1), uint32_t(m.uvs.size() - 1)});
        Expect e;
        e.extraStep = 0.1 / 8;  // the collapsed column's 3D width
        add("uvZeroAreaTriangles", stockinette, m, withRepeats(7, 8), e,
            [](const Scene& s) { EXPECT_EQ(s.grid().degenerateUvFaces, 2u * 8 + 1); });
    }

    // Near-zero-area UV triangles: a column 1e-13 wide in UV (aspect ratio ~1e12) but of normal
    // width in 3D; the UV grid, point location and stretch stay finite.
    {
        const double w = 1e-13;
        BaseMesh m = sheet(
            "near-zero-area-uv", 8, 8, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.0); },
            [w](double s, double t) {
                const double u = s <= 0.5 ? s : (s < 0.5 + 1e-9 + 1.0 / 8 ? 0.5 + w : s - 1.0 / 8 + w);
                return glm::dvec2(u, t);
            });
        Expect e;
        e.boundedSteps = false;  // stretch ~1e12 in the sliver column: the bound says nothing
        add("uvNearZeroAreaTriangles", stockinette, m, withRepeats(7, 8), e, [](const Scene& s) {
            // No segment is longer than the column plus a stitch.
            double worst = 0;
            const Polylines& c = s.yarns().curves;
            for (size_t y = 0; y < c.curveCount(); ++y)
                for (uint32_t k = 0; k + 1 < c.size(y); ++k)
                    worst = std::max(worst, glm::distance(c.points[c.begin(y) + k], c.points[c.begin(y) + k + 1]));
            EXPECT_LT(worst, 0.1 / 8 + 0.1 / 7);
        });
    }

    // A mirrored chart (u -> -u: clockwise UV triangles): points located exactly, heights along
    // the 3D normal (+z), the knit mirrored in 3D.
    add("uvMirroredChart", stockinette,
        sheet(
            "mirrored", 8, 8, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.0); },
            [](double s, double t) { return glm::dvec2(-s, t); }),
        withRepeats(6, 6), {}, [](const Scene& s) {
            EXPECT_EQ(s.grid().faceOrientation[0], -1);
            EXPECT_LT(planeMappingError(s, 0.1, glm::dvec2(0.0), true), 1e-12);
        });

    // A cylinder made of two charts, the second mirrored (a symmetric garment's halves):
    // s in [0, 1/2] has u = s, s in [1/2, 1] has u = 3/2 - s. With an even number of repeats
    // the pattern phase matches at both seams and every full course closes through two welds;
    // with an odd number it does not, and nothing is welded.
    for (const int U : {20, 21}) {
        auto half = [](bool mirrored) {
            return sheet(
                mirrored ? "mirrored-half" : "half", 12, 8,
                [mirrored](double s, double t) { return onCylinder(0.05, 0.1, mirrored ? 0.5 + s / 2 : s / 2, t); },
                [mirrored](double s, double t) { return glm::dvec2(mirrored ? 1.0 - s / 2 : s / 2, t); });
        };
        BaseMesh m = half(false);
        m.name = "two-charts-one-mirrored";
        append(m, half(true));
        weldPositions(m);
        Expect e;
        if (U % 2 == 0) e.closedLoops = 7;
        else e.weldedEnds = 0;
        add(U % 2 == 0 ? "uvMirroredHalvesEvenRepeatsClose" : "uvMirroredHalvesOddRepeatsStayOpen", stockinette, m,
            withRepeats(U, 8), e);
    }

    // UVs outside [0,1], negative, and far from the UV origin (tile indices ~1e5).
    for (const glm::dvec2 origin : {glm::dvec2(-3.3, -2.2), glm::dvec2(1e4 + 0.25, -7e3 - 0.5)}) {
        const bool far = origin.x > 1;
        add(far ? "uvFarFromUvOrigin" : "uvNegativeOutsideUnitSquare", stockinette,
            sheet(
                "offset-uv", 8, 8, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.0); },
                [origin](double s, double t) { return origin + glm::dvec2(s, t); }),
            withRepeats(9, 9), {}, [origin, far](const Scene& s) {
                EXPECT_LT(planeMappingError(s, 0.1, origin), far ? 1e-10 : 1e-12);
                EXPECT_LT(s.grid().minCell.y, 0);
            });
    }

    // Overlapping charts: two sheets (z = 0 and z = 0.05) over the same UV square. Detected
    // exactly; each chart is tiled and bound on its own, so both sheets get the same knit.
    {
        BaseMesh m = flatSquare(8, 0.1);
        m.name = "overlapping-charts";
        append(m, sheet(
                      "upper", 8, 8, [](double s, double t) { return glm::dvec3(s * 0.1, t * 0.1, 0.05); },
                      [](double s, double t) { return glm::dvec2(s, t); }));
        add("uvOverlappingCharts", stockinette, m, withRepeats(7, 7), {}, [](const Scene& s) {
            EXPECT_EQ(s.grid().overlappingIslands, (std::vector<glm::uvec2>{{0, 1}}));
            const size_t half = s.mesh().faceCount() / 2;
            size_t lower = 0, upper = 0;
            for (uint32_t f : s.binding().face) (f < half ? lower : upper)++;
            EXPECT_GT(lower, 0u);
            EXPECT_EQ(upper, lower);
            // Chart 0's yarns first, then chart 1's: the same curves, 0.05 higher.
            const Polylines& c = s.yarns().curves;
            ASSERT_EQ(c.curveCount() % 2, 0u);
            const size_t n = c.curveCount() / 2;
            double worst = 0;
            for (size_t k = 0; k < n; ++k) {
                ASSERT_EQ(c.size(k), c.size(k + n)) << "yarn " << k;
                for (uint32_t i = 0; i < c.size(k); ++i)
                    worst = std::max(worst, glm::distance(c.points[c.begin(k) + i] + glm::dvec3(0, 0, 0.05),
                                                          c.points[c.begin(k + n) + i]));
            }
            EXPECT_LT(worst, 1e-12);
        });
    }

    // Partly overlapping charts next to a touching one: sheet A over uv [0,1]^2 (z = 0), sheet B
    // over [0.5,1.5] x [0,1] (z = 0.05, overlapping A's right half), sheet C over [1.5,2.5] x
    // [0,1] touching B along u = 1.5 (z = 0.05, continuing B in 3D). Every chart gets its own
    // knit; the generic invariants check each yarn ends on its chart's boundary and steps stay
    // short (no yarn leaks into another chart).
    {
        BaseMesh m = flatSquare(8, 0.1);
        m.name = "partly-overlapping-charts";
        for (const double u0 : {0.5, 1.5})
            append(m, sheet(
                          "sheet", 8, 8, [u0](double s, double t) { return glm::dvec3((u0 + s) * 0.1, t * 0.1, 0.05); },
                          [u0](double s, double t) { return glm::dvec2(u0 + s, t); }));
        weldPositions(m);  // B and C share their edge in 3D
        add("uvPartlyOverlappingCharts", stockinette, m, withRepeats(14, 7), {}, [](const Scene& s) {
            EXPECT_EQ(s.grid().islandCount, 3u);
            EXPECT_EQ(s.grid().overlappingIslands, (std::vector<glm::uvec2>{{0, 1}}));
            std::vector<size_t> perIsland(3, 0);
            for (uint32_t f : s.binding().face) ++perIsland[s.grid().islandOfFace[f]];
            for (int c = 0; c < 3; ++c) EXPECT_GT(perIsland[size_t(c)], 0u) << "chart " << c;
            // Courses run on from B into C across their shared 3D edge: welded there.
            EXPECT_GT(s.bindStats().weldedEnds, 0u);
            // Equal UV areas and the same pattern: similar amounts of yarn on each (the two
            // layouts differ only in phase at the borders).
            EXPECT_LT(double(std::max(perIsland[0], perIsland[1])) / double(std::min(perIsland[0], perIsland[1])), 1.1);
        });
    }

    // Several charts with seams: a cylinder cut into three charts laid side by side in UV with
    // gaps. A gap of a whole number of cells keeps the pattern phase across each seam (courses
    // close through three welds); another gap does not (ends stay open, no weld).
    for (const double gap : {3.0 / 24, 0.13}) {
        BaseMesh m;
        m.name = "three-charts";
        for (int k = 0; k < 3; ++k)
            append(m, sheet(
                          "chart", 8, 8, [k](double s, double t) { return onCylinder(0.05, 0.1, (k + s) / 3, t); },
                          [k, gap](double s, double t) { return glm::dvec2((k + s) / 3 + k * gap, t); }));
        weldPositions(m);
        Expect e;
        const bool matching = gap == 3.0 / 24;
        // Phase shifted by 0.12 period at each seam: no course closes (a few crossings may still
        // meet within the weld tolerance by chance; the step bound checks those welds).
        e.closedLoops = matching ? 7 : 0;
        add(matching ? "uvThreeChartsWholeCellGapsClose" : "uvThreeChartsOtherGapsStayOpen", stockinette, m,
            withRepeats(24, 8), e, [](const Scene& s) {
                EXPECT_EQ(s.grid().islandCount, 3u);
                EXPECT_TRUE(s.grid().overlappingIslands.empty());  // side by side: no overlap
            });
    }

    // The cylinder seam: integral repeats close every full course; non-integral ones do not and
    // weld nothing.
    {
        ProceduralMeshOptions mo;
        mo.resU = 48;
        mo.resV = 12;
        Expect closes;
        closes.closedLoops = 7;
        add("cylinderSeamIntegralRepeats", stockinette, makeCylinder(mo), withRepeats(20, 8), closes);
        Expect open;
        open.closedLoops = 0;
        open.weldedEnds = 0;
        add("cylinderSeamNonIntegralRepeats", stockinette, makeCylinder(mo), withRepeats(20.5, 8), open);
    }

    // A UV island smaller than one pattern cell (0.3 x 0.3 of a cell): a few short pieces, cut
    // at the island's boundary.
    {
        Expect e;
        e.allowEmpty = true;
        add("uvIslandSmallerThanOneCell", stockinette,
            sheet(
                "small-island", 4, 4, [](double s, double t) { return glm::dvec3(s * 0.003, t * 0.003, 0.0); },
                [](double s, double t) { return glm::dvec2(0.2 + 0.3 * s, 0.35 + 0.3 * t); }),
            withRepeats(1, 1), e, [](const Scene& s) {
                EXPECT_LE(s.grid().cells.size(), 1u);
                EXPECT_GT(s.bindStats().cutVertices, 0u);
            });
    }

    // A U-shaped chart whose arms are closer in UV than one pattern step but far apart in 3D
    // (a folded layout, like a garment's legs): a course stepping over the gap between the arms
    // must be cut at both arms, never joined by a segment through the air.
    {
        // Arms u in [0, 0.45] and [0.55, 1], joined for v in [0.8, 1]; in 3D the right arm
        // rises to z = 0.2 m at v = 0. Straight courses with vertices at u = 0.10 + 0.16 k step
        // from u = 0.42 to u = 0.58, over the gap.
        BaseMesh m;
        m.name = "u-shaped-chart";
        const int nu = 20, nv = 20;
        for (int j = 0; j <= nv; ++j)
            for (int i = 0; i <= nu; ++i) {
                const glm::dvec2 uv(double(i) / nu, double(j) / nv);
                m.uvs.push_back(uv);
                m.positions.emplace_back(uv.x * 0.1, uv.y * 0.1, uv.x > 0.5 ? 0.25 * std::max(0.0, 0.8 - uv.y) : 0.0);
            }
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const double uc = (i + 0.5) / nu, vc = (j + 0.5) / nv;
                if (uc > 0.45 && uc < 0.55 && vc < 0.8) continue;  // the gap between the arms
                const uint32_t a = j * (nu + 1) + i, b = a + 1, c = b + nu + 1, d = a + nu + 1;
                m.faces.push_back({a, b, c});
                m.faces.push_back({a, c, d});
            }
        m.faceUvs = m.faces;
        add("uvNotchNarrowerThanAStepIsCut", straightCourses(0.01, 0.01, 0.0005, 0.005, 1, 0.625 * 0.01), m,
            withRepeats(6.25, 12), {}, [](const Scene& s) {
                // Courses below v = 0.8 are cut at both arms: more open yarns than courses.
                EXPECT_GT(s.yarns().curves.curveCount(), 12u);
            });
    }

    // ======================= 3D ==============================================================
    // Slivers with aspect ratio 1e6: every other column 1e-6 of the normal width, in UV and 3D
    // (like the core tests' slivers), and in 3D only (regular UVs, 3D compressed).
    for (const bool uvToo : {true, false}) {
        // Column widths alternate W and 1e-6 W (x of vertex column i).
        auto x = [](double s) {
            const int i = int(std::lround(s * 8));
            const double W = 1.0 / (4 * (1 + 1e-6));
            return ((i + 1) / 2) * W + (i / 2) * W * 1e-6;
        };
        BaseMesh m = sheet(
            "slivers", 8, 8, [x](double s, double t) { return glm::dvec3(x(s) * 0.1, t * 0.1, 0.0); },
            [x, uvToo](double s, double t) { return glm::dvec2(uvToo ? x(s) : s, t); });
        add(uvToo ? "slivers3dAndUvAspect1e6" : "slivers3dOnlyAspect1e6", stockinette, m, withRepeats(7, 8), {},
            [uvToo](const Scene& s) {
                if (uvToo) EXPECT_LT(planeMappingError(s, 0.1), 1e-9);
            });
    }

    // Zero-area 3D triangles with valid UVs: a column of the sheet collapsed in 3D (positions
    // equal, distinct indices) and a second one welded (faces repeating a position index).
    for (const bool welded : {false, true}) {
        BaseMesh m = sheet(
            "zero-area-3d", 8, 8,
            [](double s, double t) {
                return glm::dvec3(std::min(s, 0.5) * 0.1 + std::max(0.0, s - 0.625) * 0.1, t * 0.1, 0.0);
            },
            [](double s, double t) { return glm::dvec2(s, t); });
        if (welded) weldPositions(m);
        add(welded ? "zeroArea3dTrianglesWelded" : "zeroArea3dTriangles", stockinette, m, withRepeats(7, 8), {},
            [](const Scene& s) {
                for (const glm::dvec3& n : s.normals()) EXPECT_NEAR(n.z, 1.0, 1e-12);
            });
    }

    // Non-manifold edge: three square pages sharing one edge (a book), each its own UV chart.
    {
        BaseMesh m;
        m.name = "book";
        for (int k = 0; k < 3; ++k) {
            const double a = 2 * kPi * k / 3 + 0.3;
            append(m, sheet(
                          "page", 6, 6,
                          [a](double s, double t) {
                              return glm::dvec3(s * 0.05, t * 0.05 * std::cos(a), t * 0.05 * std::sin(a));
                          },
                          [k](double s, double t) { return glm::dvec2(s, t + 1.1 * k) / 3.3; }));
        }
        weldPositions(m);
        add("nonManifoldEdge", stockinette, m, withRepeats(10, 10));
    }

    // Non-manifold vertex: two squares touching at one corner (a bowtie), UV and 3D.
    {
        BaseMesh m = flatSquare(4, 0.05);
        m.name = "bowtie";
        append(m, sheet(
                      "other", 4, 4,
                      [](double s, double t) { return glm::dvec3(0.05 + s * 0.05, 0.05 + t * 0.05, 0.01 * s * t); },
                      [](double s, double t) { return glm::dvec2(1 + s, 1 + t); }));
        weldPositions(m);
        add("nonManifoldVertex", stockinette, m, withRepeats(6, 6));
    }

    // Isolated vertices (positions and UVs no face uses, one of them huge): no effect at all.
    {
        BaseMesh m = makeDrape({});
        m.positions.push_back({1e30, -1e30, 5});
        m.positions.push_back({0, 0, 0});
        m.uvs.push_back({1e20, -1e20});
        add("isolatedVertices", stockinette, m, withRepeats(12, 12), {}, [](const Scene& s) {
            const Scene clean = buildScene(generateStockinette(), makeDrape({}), withRepeats(12, 12));
            ASSERT_EQ(clean.yarns().curves.pointCount(), s.yarns().curves.pointCount());
            for (size_t i = 0; i < clean.yarns().curves.pointCount(); ++i)
                ASSERT_EQ(clean.yarns().curves.points[i], s.yarns().curves.points[i]);
        });
    }

    // Inconsistent orientation: some triangles of the drape wound the other way (3D and UV
    // corners reversed together): every third triangle, or a whole quarter of the sheet. Heights
    // follow the side of the larger consistently wound area: the same yarns as the clean drape.
    for (const bool quarter : {false, true}) {
        BaseMesh m = makeDrape({});
        m.name = "flipped-drape";
        for (size_t f = 0; f < m.faces.size(); ++f) {
            const glm::dvec3 centre =
                (m.positions[m.faces[f].x] + m.positions[m.faces[f].y] + m.positions[m.faces[f].z]) / 3.0;
            if (quarter ? (centre.x < 0 && centre.y < 0) : f % 3 == 0) {
                std::swap(m.faces[f].y, m.faces[f].z);
                std::swap(m.faceUvs[f].y, m.faceUvs[f].z);
            }
        }
        add(quarter ? "inconsistentOrientationFlippedQuarter" : "inconsistentOrientationEveryThirdFace", stockinette, m,
            withRepeats(12, 12), {}, [](const Scene& s) {
                const Scene clean = buildScene(generateStockinette(), makeDrape({}), withRepeats(12, 12));
                ASSERT_EQ(clean.yarns().curves.pointCount(), s.yarns().curves.pointCount());
                double worst = 0;
                for (size_t i = 0; i < clean.yarns().curves.pointCount(); ++i)
                    worst = std::max(worst, glm::distance(clean.yarns().curves.points[i], s.yarns().curves.points[i]));
                EXPECT_LT(worst, 1e-12) << "heights differ from the consistently oriented drape";
            });
    }

    // A mesh 1e5 m from the origin: the same yarns as at the origin, shifted, to ~1e-10 m.
    {
        const glm::dvec3 shift(1e5, -1e5, 3e4);
        BaseMesh m = makeDrape({});
        for (glm::dvec3& p : m.positions) p += shift;
        add("meshFarFromOrigin1e5", stockinette, m, withRepeats(12, 12), {}, [shift](const Scene& s) {
            const Scene home = buildScene(generateStockinette(), makeDrape({}), withRepeats(12, 12));
            ASSERT_EQ(home.yarns().curves.pointCount(), s.yarns().curves.pointCount());
            double worst = 0;
            for (size_t i = 0; i < home.yarns().curves.pointCount(); ++i)
                worst =
                    std::max(worst, glm::distance(home.yarns().curves.points[i] + shift, s.yarns().curves.points[i]));
            EXPECT_LT(worst, 1e-9);
            ASSERT_EQ(home.plies().curves.pointCount(), s.plies().curves.pointCount());
            double plyWorst = 0;
            for (size_t i = 0; i < home.plies().curves.pointCount(); ++i)
                plyWorst = std::max(plyWorst,
                                    glm::distance(home.plies().curves.points[i] + shift, s.plies().curves.points[i]));
            EXPECT_LT(plyWorst, 1e-8);
        });
    }

    // Tiny (1e-4 m) and huge (1e3 m) scales with explicit repeats: the unit-size result scaled
    // (radii and heights scale with the period), to 1e-9 relative.
    for (const double scale : {1e-4, 1e3}) {
        BaseMesh m = makeDrape({});
        for (glm::dvec3& p : m.positions) p *= scale / 0.5;
        add(scale < 1 ? "tinyScale1em4" : "hugeScale1e3", stockinette, m, withRepeats(10, 10), {},
            [scale](const Scene& s) {
                BaseMesh unit = makeDrape({});
                for (glm::dvec3& p : unit.positions) p *= 1.0 / 0.5;
                const Scene u = buildScene(generateStockinette(), unit, withRepeats(10, 10));
                ASSERT_EQ(u.yarns().curves.pointCount(), s.yarns().curves.pointCount());
                double worst = 0;
                for (size_t i = 0; i < u.yarns().curves.pointCount(); ++i)
                    worst = std::max(
                        worst, glm::distance(u.yarns().curves.points[i] * scale, s.yarns().curves.points[i]) / scale);
                EXPECT_LT(worst, 1e-9);
                EXPECT_NEAR(s.yarnRadius() / u.yarnRadius(), scale, 1e-12 * scale);
            });
    }
    // The same scales at the pattern's physical size: the tiny mesh is smaller than one stitch
    // (a few pieces or nothing); the huge one would need ~1e10 cells and is refused.
    {
        BaseMesh tiny = flatSquare(4, 1e-4);
        SceneOptions physical;
        Expect e;
        e.allowEmpty = true;
        add("tinyScalePhysicalSize", stockinette, tiny, physical, e);
        BaseMesh huge = flatSquare(4, 1e3);
        Expect err;
        err.errorHas = "pattern cells";
        add("hugeScalePhysicalSizeIsRefused", stockinette, huge, physical, err);
    }

    // A crumpled surface whose height offset self-intersects: a thin cylinder (radius 0.6 mm)
    // under yarn heights of +-1.25 mm: the inner offset passes through the axis. No crash, no
    // NaN; the fold is detected (foldedOffsetVertices) — and the same pattern on a wide cylinder
    // has none.
    {
        ProceduralMeshOptions mo;
        mo.resU = 24;
        mo.resV = 6;
        mo.radius = 0.0006;
        mo.height = 0.02;
        SceneOptions o = withRepeats(1, 3);
        add("crumpledOffsetSelfIntersects", stockinette, makeCylinder(mo), o, {},
            [](const Scene& s) { EXPECT_GT(foldedOffsetVertices(s), 0u); });
        mo.radius = 0.05;
        add("wideCylinderOffsetDoesNotFold", stockinette, makeCylinder(mo), withRepeats(40, 3), {},
            [](const Scene& s) { EXPECT_EQ(foldedOffsetVertices(s), 0u); });
    }

    // ======================= curves ==========================================================
    // Straight runs: straight courses on a plane (no curvature anywhere): plies are exact
    // helices at the centre radius.
    add("curvesStraightRuns", straightCourses(0.01, 0.01, 0.001, 0.005), flatSquare(4, 0.1), withRepeats(10, 10), {},
        [](const Scene& s) {
            const Plies& p = s.plies();
            ASSERT_GT(p.curves.pointCount(), 0u);
            // Each straight course lies at y = const, z = 0: ply points at distance R from it.
            for (size_t k = 0; k < p.curves.curveCount(); ++k) {
                const glm::dvec3 a = s.yarns().curves.points[s.yarns().curves.begin(p.yarnOfCurve[k])];
                for (uint32_t i = p.curves.begin(k); i < p.curves.end(k); ++i) {
                    const glm::dvec3 q = p.curves.points[i];
                    ASSERT_NEAR(std::hypot(q.y - a.y, q.z - a.z), p.centerRadius, 1e-12);
                }
            }
        });

    // Hairpins tighter than the ply offset (turn radius 0.3 yarn radii, plies at 0.5).
    add("curvesHairpinTighterThanPlyOffset", hairpinPattern(), flatSquare(4, 0.1), withRepeats(10, 10));

    // Repeated points: every stockinette vertex twice (zero-length edges). The yarns have the
    // same shape: the plies have the same total length.
    add("curvesRepeatedPoints", doubledPoints(stockinette), makeDrape({}), withRepeats(12, 12), {}, [](const Scene& s) {
        const Scene plain = buildScene(generateStockinette(), makeDrape({}), withRepeats(12, 12));
        auto totalLength = [](const Polylines& c) {
            double sum = 0;
            for (size_t y = 0; y < c.curveCount(); ++y)
                for (uint32_t k = 0; k < c.segmentCount(y); ++k)
                    sum += glm::distance(c.points[c.begin(y) + k], c.points[c.begin(y) + (k + 1) % c.size(y)]);
            return sum;
        };
        EXPECT_EQ(plain.yarns().curves.curveCount(), s.yarns().curves.curveCount());
        EXPECT_NEAR(totalLength(s.plies().curves), totalLength(plain.plies().curves),
                    1e-9 * totalLength(plain.plies().curves));
    });

    // Closed loops whose length is not a whole number of ply turns (and whose RMF does not
    // close by itself): turns are rounded, the plies close with no jump.
    {
        SceneOptions o = withRepeats(8, 8);
        o.plies.pitch = 0.0047;  // loop length / pitch ~ 4.37 (not whole)
        Expect e;
        e.closedLoops = 64;  // 8 x 8 tiles inside the square; the far border's rings are cut
        add("curvesClosedLoopNonIntegerTwist", ringPattern(), flatSquare(4, 0.08), o, e, [](const Scene& s) {
            const Polylines& c = s.plies().curves;
            for (size_t k = 0; k < c.curveCount(); ++k) {
                if (!c.isClosed(k)) continue;
                double longest = 0;
                for (uint32_t i = c.begin(k); i + 1 < c.end(k); ++i)
                    longest = std::max(longest, glm::distance(c.points[i], c.points[i + 1]));
                EXPECT_LE(glm::distance(c.points[c.end(k) - 1], c.points[c.begin(k)]), 1.5 * longest) << "ply " << k;
            }
        });
    }

    // Points just outside the boundary, within the clamp tolerance: a straight course at
    // v = -1.25e-8 (the tolerance is 0.01 yarn radii = 1.25e-4 in UV here) is clamped onto the
    // boundary, not cut.
    add("uvPointsJustOutsideAreClamped", straightCourses(0.01, 0.01, 0.001, -1e-9, 4), flatSquare(4, 0.08),
        withRepeats(8, 8), {}, [](const Scene& s) {
            EXPECT_GT(s.bindStats().clampedVertices, 0u);
            // The course at v ~ 0 survives: 9 courses (v ~ 0, 1/8, ..., 1).
            EXPECT_EQ(s.yarns().curves.curveCount(), 9u);
            for (const glm::dvec3& p : s.yarns().curves.points) EXPECT_GE(p.y, 0.0);
        });

    return cases;
}

// Names of the catalogue's cases (for INSTANTIATE_TEST_SUITE_P).
inline std::vector<std::string> catalogueNames() {
    std::vector<std::string> names;
    for (const HardCase& c : catalogue()) names.push_back(c.name);
    return names;
}

inline HardCase catalogueCase(const std::string& name) {
    for (HardCase& c : catalogue())
        if (c.name == name) return std::move(c);
    throw std::runtime_error("no hard case " + name);
}

}  // namespace knit::hard
