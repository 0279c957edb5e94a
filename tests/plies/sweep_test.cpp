// Tube sweep (knit/sweep.hpp): ring geometry, layout, watertightness, determinism.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include <tbb/global_control.h>

#include "export/test_curves.hpp"
#include "knit/sweep.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

Polylines single(const std::vector<glm::dvec3>& p, bool closed) {
    Polylines c;
    c.addCurve(p.data(), p.size(), closed);
    return c;
}

glm::dvec3 pos(const TubeMesh& m, size_t i) { return m.origin + glm::dvec3(m.positions[i]); }

TEST(Sweep, countsMatchLayoutForOpenClosedAndShortCurves) {
    TubeOptions o;
    o.sides = 7;
    EXPECT_EQ(tubeVertexCount(10, false, o), 10u * 8 + 2 * 8);
    EXPECT_EQ(tubeVertexCount(10, true, o), 11u * 8);
    EXPECT_EQ(tubeTriangleCount(10, false, o), 9u * 14 + 14);
    EXPECT_EQ(tubeTriangleCount(10, true, o), 10u * 14);
    EXPECT_EQ(tubeVertexCount(1, false, o), 0u);
    o.caps = false;
    EXPECT_EQ(tubeVertexCount(10, false, o), 80u);
    EXPECT_EQ(tubeTriangleCount(10, false, o), 9u * 14);
    Polylines c = test::mixedCurves();
    const glm::dvec3 one(0.0);
    c.addCurve(&one, 1, false);
    const TubeMesh m = sweepTubes(c, 0.001, o, 0, c.curveCount(), glm::dvec3(0));
    size_t v = 0, t = 0;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        v += tubeVertexCount(c.size(k), c.isClosed(k), o);
        t += tubeTriangleCount(c.size(k), c.isClosed(k), o);
    }
    EXPECT_EQ(m.vertexCount(), v);
    EXPECT_EQ(m.triangles.size(), t);
    EXPECT_EQ(m.normals.size(), v);
    EXPECT_EQ(m.tangents.size(), v);
    EXPECT_EQ(m.uvs.size(), v);
    EXPECT_EQ(m.curveOfVertex.size(), v);
}

TEST(Sweep, ringsAreOneRadiusOutAndPerpendicularToAveragedTangent) {
    const auto p = test::helix(60, 0.01, 0.006, 3.0, glm::dvec3(5, 6, 7));
    const Polylines c = single(p, false);
    TubeOptions o;
    o.sides = 9;
    const double r = 0.0007;
    const glm::dvec3 origin(5, 6, 7);
    const TubeMesh m = sweepTubes(c, r, o, 0, 1, origin);
    for (size_t i = 0; i < p.size(); ++i) {
        const glm::dvec3 dPrev = i > 0 ? glm::normalize(p[i] - p[i - 1]) : glm::dvec3(0);
        const glm::dvec3 dNext = i + 1 < p.size() ? glm::normalize(p[i + 1] - p[i]) : glm::dvec3(0);
        const glm::dvec3 t = glm::normalize(dPrev + dNext);
        for (int j = 0; j <= o.sides; ++j) {
            const size_t v = i * 10 + size_t(j);
            const glm::dvec3 d = pos(m, v) - p[i];
            EXPECT_NEAR(glm::length(d), r, 1e-7 * 0.02 + 1e-9) << i << "/" << j;
            EXPECT_NEAR(glm::dot(d, t) / r, 0.0, 1e-5) << "ring " << i << " not perpendicular";
            EXPECT_NEAR(glm::length(glm::dvec3(m.normals[v]) - d / r), 0.0, 1e-4);
            // glTF TANGENT: along increasing u (around the ring, t x normal), w = +1.
            EXPECT_NEAR(glm::length(glm::dvec3(m.tangents[v]) - glm::cross(t, d / r)), 0.0, 1e-4);
            EXPECT_EQ(m.tangents[v].w, 1.0f);
            EXPECT_EQ(m.curveOfVertex[v], 0u);
        }
    }
}

TEST(Sweep, seamColumnRepeatsFirstVertexWithUOne) {
    const Polylines c = single(test::helix(12, 0.01, 0.004, 1.0), false);
    TubeOptions o;
    o.sides = 6;
    const TubeMesh m = sweepTubes(c, 0.001, o, 0, 1, glm::dvec3(0));
    for (size_t ring = 0; ring < 12; ++ring) {
        const size_t a = ring * 7, b = a + 6;
        EXPECT_EQ(m.positions[a], m.positions[b]);
        EXPECT_EQ(m.normals[a], m.normals[b]);
        EXPECT_EQ(m.uvs[a].x, 0.0f);
        EXPECT_EQ(m.uvs[b].x, 1.0f);
        EXPECT_EQ(m.uvs[a].y, m.uvs[b].y);
        for (int j = 0; j < 6; ++j) EXPECT_FLOAT_EQ(m.uvs[a + size_t(j)].x, float(j) / 6.0f);
    }
}

TEST(Sweep, vCoordinateIsArcLengthInRadiusUnits) {
    const std::vector<glm::dvec3> p{{0, 0, 0}, {0.003, 0, 0}, {0.003, 0.004, 0}, {0.003, 0.004, 0.012}};
    const Polylines c = single(p, false);
    TubeOptions o;
    o.sides = 4;
    const double r = 0.002;
    const TubeMesh m = sweepTubes(c, r, o, 0, 1, glm::dvec3(0));
    const double s[4] = {0, 0.003, 0.007, 0.019};
    for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(m.uvs[i * 5].y, s[i] / r, 1e-5) << i;
}

TEST(Sweep, closedLoopLastRingCoincidesWithFirstAndVKeepsGrowing) {
    const auto p = test::circle(40, 0.02);
    const Polylines c = single(p, true);
    TubeOptions o;
    o.sides = 8;
    const double r = 0.001;
    const TubeMesh m = sweepTubes(c, r, o, 0, 1, glm::dvec3(0));
    ASSERT_EQ(m.vertexCount(), 41u * 9);
    for (int j = 0; j <= 8; ++j) {
        EXPECT_LT(glm::length(glm::dvec3(m.positions[size_t(j)] - m.positions[40 * 9 + size_t(j)])), 1e-7)
            << "closing ring differs at " << j;
        EXPECT_LT(glm::length(glm::dvec3(m.normals[size_t(j)] - m.normals[40 * 9 + size_t(j)])), 1e-5);
    }
    const double length = 40 * 2 * 0.02 * std::sin(util::kPi / 40);
    EXPECT_NEAR(m.uvs[40 * 9].y, length / r, 1e-3);
    for (size_t i = 1; i <= 40; ++i) EXPECT_GT(m.uvs[i * 9].y, m.uvs[(i - 1) * 9].y);
}

// Edges of the mesh after welding vertices with identical positions: a closed surface has every
// undirected edge used exactly twice, once in each direction.
size_t openEdges(const TubeMesh& m) {
    std::map<std::tuple<float, float, float>, uint32_t> weld;
    std::vector<uint32_t> id(m.vertexCount());
    for (size_t i = 0; i < m.vertexCount(); ++i) {
        const auto key = std::make_tuple(m.positions[i].x, m.positions[i].y, m.positions[i].z);
        id[i] = weld.emplace(key, uint32_t(weld.size())).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const glm::uvec3& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{id[t[k]], id[t[(k + 1) % 3]]}];
    size_t bad = 0;
    for (const auto& [e, n] : directed) {
        auto back = directed.find({e.second, e.first});
        if (n != 1 || back == directed.end() || back->second != 1) ++bad;
    }
    return bad;
}

TEST(Sweep, cappedOpenTubeIsWatertightAfterWeldingByPosition) {
    const Polylines c = single(test::helix(30, 0.01, 0.004, 2.0, glm::dvec3(1, 1, 1)), false);
    TubeOptions o;
    o.sides = 7;
    const TubeMesh m = sweepTubes(c, 0.001, o, 0, 1, glm::dvec3(1, 1, 1));
    EXPECT_EQ(openEdges(m), 0u);
    o.caps = false;
    EXPECT_GT(openEdges(sweepTubes(c, 0.001, o, 0, 1, glm::dvec3(1, 1, 1))), 0u) << "uncapped ends are open";
}

TEST(Sweep, closedLoopTubeIsWatertightWithoutCaps) {
    const Polylines c = single(test::circle(24, 0.01), true);
    TubeOptions o;
    o.sides = 5;
    const TubeMesh m = sweepTubes(c, 0.001, o, 0, 1, glm::dvec3(0));
    EXPECT_EQ(openEdges(m), 0u);
}

TEST(Sweep, trianglesFaceOutwardLikeTheirVertexNormals) {
    const Polylines c = test::mixedCurves();
    TubeOptions o;
    o.sides = 6;
    const TubeMesh m = sweepTubes(c, 0.001, o, 0, c.curveCount(), glm::dvec3(0));
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const glm::uvec3 t = m.triangles[f];
        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), d(m.positions[t.z]);
        const glm::dvec3 g = glm::cross(b - a, d - a);
        const glm::dvec3 n = glm::dvec3(m.normals[t.x]) + glm::dvec3(m.normals[t.y]) + glm::dvec3(m.normals[t.z]);
        ASSERT_GT(glm::dot(g, n), 0.0) << "triangle " << f << " winds inward";
    }
}

TEST(Sweep, capVerticesPointAlongTheAxis) {
    const std::vector<glm::dvec3> p{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    TubeOptions o;
    o.sides = 4;
    const TubeMesh m = sweepTubes(single(p, false), 0.1, o, 0, 1, glm::dvec3(0));
    const size_t start = 3 * 5, end = 4 * 5;
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(glm::dvec3(m.normals[start + i]), glm::dvec3(-1, 0, 0));
        EXPECT_EQ(glm::dvec3(m.normals[end + i]), glm::dvec3(1, 0, 0));
    }
    EXPECT_EQ(glm::dvec3(m.positions[start]), glm::dvec3(0, 0, 0));
    EXPECT_EQ(glm::dvec3(m.positions[end]), glm::dvec3(2, 0, 0));
}

TEST(Sweep, seedNormalFixesRingPhase) {
    const std::vector<glm::dvec3> p{{0, 0, 0}, {1, 0, 0}, {2, 0.1, 0}, {3, 0, 0}};
    const std::vector<glm::dvec3> seeds(4, glm::dvec3(0, 0, 1));
    TubeOptions o;
    o.sides = 8;
    o.seedNormals = &seeds;
    const TubeMesh m = sweepTubes(single(p, false), 0.1, o, 0, 1, glm::dvec3(0));
    // Vertex 0 of the first ring points along the seed (projected perpendicular to the tangent).
    EXPECT_NEAR(glm::length(glm::dvec3(m.normals[0]) - glm::dvec3(0, 0, 1)), 0.0, 1e-6);
}

TEST(Sweep, straightRunHasNoTwist) {
    std::vector<glm::dvec3> p;
    for (int i = 0; i < 20; ++i) p.emplace_back(0.1 * i, 0.05 * i, -0.02 * i);
    TubeOptions o;
    o.sides = 6;
    const TubeMesh m = sweepTubes(single(p, false), 0.01, o, 0, 1, glm::dvec3(0));
    for (size_t i = 1; i < 20; ++i)
        for (size_t j = 0; j < 7; ++j) ASSERT_LT(glm::length(m.normals[i * 7 + j] - m.normals[j]), 1e-6f);
}

TEST(Sweep, coincidentPointsGiveFiniteUnitNormals) {
    const std::vector<glm::dvec3> p(5, glm::dvec3(0.5, 0.5, 0.5));
    TubeOptions o;
    o.sides = 5;
    const TubeMesh m = sweepTubes(single(p, false), 0.01, o, 0, 1, glm::dvec3(0.5, 0.5, 0.5));
    ASSERT_GT(m.vertexCount(), 0u);
    for (size_t i = 0; i < m.vertexCount(); ++i) {
        ASSERT_TRUE(util::finite(m.positions[i]));
        ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-6f);
        ASSERT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-6f);
    }
}

TEST(Sweep, subRangeEqualsSliceOfFullSweep) {
    const Polylines c = test::mixedCurves();
    TubeOptions o;
    o.sides = 5;
    const TubeMesh all = sweepTubes(c, 0.001, o, 0, 3, glm::dvec3(0));
    const TubeMesh mid = sweepTubes(c, 0.001, o, 1, 2, glm::dvec3(0));
    const size_t first = tubeVertexCount(c.size(0), false, o);
    ASSERT_EQ(mid.vertexCount(), tubeVertexCount(c.size(1), true, o));
    for (size_t i = 0; i < mid.vertexCount(); ++i) {
        ASSERT_EQ(mid.positions[i], all.positions[first + i]);
        ASSERT_EQ(mid.curveOfVertex[i], 1u);
    }
    EXPECT_EQ(mid.triangles.front(),
              all.triangles[tubeTriangleCount(c.size(0), false, o)] - glm::uvec3(uint32_t(first)));
}

TEST(Sweep, resultIsIdenticalForOneAndManyThreads) {
    Polylines c;
    for (int k = 0; k < 64; ++k) {
        const auto h = test::helix(50 + k, 0.01 + 0.0001 * k, 0.003, 2.0, glm::dvec3(0.05 * k, 0, 0));
        c.addCurve(h.data(), h.size(), k % 3 == 0);
    }
    TubeOptions o;
    o.sides = 6;
    TubeMesh one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = sweepTubes(c, 0.001, o, 0, c.curveCount(), glm::dvec3(1, 0, 0));
    }
    const TubeMesh many = sweepTubes(c, 0.001, o, 0, c.curveCount(), glm::dvec3(1, 0, 0));
    EXPECT_EQ(one.positions, many.positions);
    EXPECT_EQ(one.normals, many.normals);
    EXPECT_EQ(one.tangents, many.tangents);
    EXPECT_EQ(one.uvs, many.uvs);
    EXPECT_EQ(one.triangles, many.triangles);
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

// dP/du and dP/dv of one triangle from its positions and UVs (the mesh's own parametrization).
void triangleUvGradients(const TubeMesh& m, const glm::uvec3& t, glm::dvec3& dPdu, glm::dvec3& dPdv) {
    const glm::dvec3 p0(m.positions[t[0]]), e1 = glm::dvec3(m.positions[t[1]]) - p0,
                                            e2 = glm::dvec3(m.positions[t[2]]) - p0;
    const glm::dvec2 w0(m.uvs[t[0]]), d1 = glm::dvec2(m.uvs[t[1]]) - w0, d2 = glm::dvec2(m.uvs[t[2]]) - w0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    dPdu = (e1 * d2.y - e2 * d1.y) / det;
    dPdv = (e2 * d1.x - e1 * d2.x) / det;
}

TEST(Sweep, tangentRunsAlongIncreasingUWithTheBitangentSignInW) {
    // Dense samples: consecutive ring frames differ by a few degrees only.
    const Polylines c = single(test::helix(96, 0.01, 0.004, 1.0), false);
    TubeOptions o;
    o.sides = 16;  // a ring chord (a triangle's dP/du) is within 11.25 degrees of the vertex tangent
    const TubeMesh m = sweepTubes(c, 0.0008, o, 0, 1, glm::dvec3(0.0));
    ASSERT_FALSE(m.triangles.empty());
    for (const glm::uvec3& t : m.triangles) {
        glm::dvec3 dPdu, dPdv;
        triangleUvGradients(m, t, dPdu, dPdv);
        for (int k = 0; k < 3; ++k) {
            const glm::vec4& tan = m.tangents[t[k]];
            const glm::dvec3 n(m.normals[t[k]]), tx(tan);
            // xyz points along dP/du (side rings: a chord of the ring vs its tangent, caps: exact).
            EXPECT_GT(glm::dot(tx, glm::normalize(dPdu)), 0.9) << "triangle vertex " << t[k];
            // w * cross(normal, tangent) points along dP/dv.
            EXPECT_GT(double(tan.w) * glm::dot(glm::cross(n, tx), dPdv), 0.0) << "triangle vertex " << t[k];
        }
    }
}

}  // namespace
}  // namespace knit
