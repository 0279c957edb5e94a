// Tests for the built-in meshes: +Y up, UV range and orientation, seams, poles, the drape's shape.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "util/math.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

using knit::BaseMesh;

namespace {

knit::ProceduralMeshOptions opts(int resU, int resV) {
    knit::ProceduralMeshOptions o;
    o.resU = resU;
    o.resV = resV;
    return o;
}

double uvDet(const BaseMesh& m, size_t f) {
    const glm::dvec2 a = m.uvs[m.faceUvs[f].x], b = m.uvs[m.faceUvs[f].y], c = m.uvs[m.faceUvs[f].z];
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

glm::dvec3 faceNormal(const BaseMesh& m, size_t f) {
    const glm::dvec3 a = m.positions[m.faces[f].x], b = m.positions[m.faces[f].y], c = m.positions[m.faces[f].z];
    return glm::cross(b - a, c - a);
}

glm::dvec3 centroid(const BaseMesh& m, size_t f) {
    return (m.positions[m.faces[f].x] + m.positions[m.faces[f].y] + m.positions[m.faces[f].z]) / 3.0;
}

}  // namespace

TEST(ProceduralMesh, allHaveUvsInUnitSquareCcwUvTrianglesAndOutwardNormals) {
    for (const std::string& name : knit::builtinMeshNames()) {
        const BaseMesh m = knit::builtinMesh(name, opts(7, 5));
        SCOPED_TRACE(name);
        EXPECT_EQ(m.name, name);
        ASSERT_NO_THROW(knit::validateMesh(m));
        for (const glm::dvec2& uv : m.uvs) {
            EXPECT_GE(uv.x, 0.0);
            EXPECT_LE(uv.x, 1.0);
            EXPECT_GE(uv.y, 0.0);
            EXPECT_LE(uv.y, 1.0);
        }
        for (size_t f = 0; f < m.faces.size(); ++f) {
            EXPECT_GT(uvDet(m, f), 0.0) << "face " << f;
            const glm::dvec3 n = faceNormal(m, f), c = centroid(m, f);
            // +Y up: the cylinder stands along +y, the plane and the drape face +y.
            const glm::dvec3 outward = name == "cylinder" ? glm::dvec3(c.x, 0.0, c.z)
                                       : name == "sphere" ? c
                                                          : glm::dvec3(0, 1, 0);
            EXPECT_GT(glm::dot(n, outward), 0.0) << "face " << f;
        }
        // Every UV vertex and every position is used.
        std::vector<char> usedUv(m.uvs.size(), 0), usedPos(m.positions.size(), 0);
        for (size_t f = 0; f < m.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) usedUv[m.faceUvs[f][k]] = usedPos[m.faces[f][k]] = 1;
        EXPECT_EQ(std::count(usedUv.begin(), usedUv.end(), 0), 0);
        EXPECT_EQ(std::count(usedPos.begin(), usedPos.end(), 0), 0);
    }
}

TEST(ProceduralMesh, planeLiesInYZeroWithUAlongXAndVAlongMinusZ) {
    knit::ProceduralMeshOptions o = opts(4, 3);
    o.size = 0.8;
    const BaseMesh m = knit::makePlane(o);
    ASSERT_EQ(m.faces.size(), 24u);
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = m.positions[m.faces[f][k]];
            const glm::dvec2 uv = m.uvs[m.faceUvs[f][k]];
            EXPECT_EQ(p.y, 0.0);
            EXPECT_NEAR(uv.x, p.x / o.size + 0.5, 1e-15);
            EXPECT_NEAR(uv.y, 0.5 - p.z / o.size, 1e-15);
        }
}

TEST(ProceduralMesh, cylinderSeamSharesPositionsButNotUvs) {
    const BaseMesh m = knit::makeCylinder(opts(6, 2));
    EXPECT_EQ(m.positions.size(), 6u * 3u);  // closed around: no duplicated seam column
    EXPECT_EQ(m.uvs.size(), 7u * 3u);        // u = 0 and u = 1 both exist
    // Corners at u = 1 use the same positions as corners at u = 0 (angle 0).
    size_t seamCorners = 0;
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec2 uv = m.uvs[m.faceUvs[f][k]];
            const glm::dvec3 p = m.positions[m.faces[f][k]];
            EXPECT_NEAR(p.y, uv.y * 0.3, 1e-15);  // v along +y
            if (uv.x == 1.0 || uv.x == 0.0) {
                EXPECT_EQ(p.x, 0.1);
                EXPECT_EQ(p.z, 0.0);
                ++seamCorners;
            }
        }
    EXPECT_GT(seamCorners, 0u);
}

TEST(ProceduralMesh, cylinderNormalsContinuousAcrossSeam) {
    // Every quad contributes its full corner angle (90°) times its flat normal, and the quads
    // left and right of a vertex are mirror images, so the angle-weighted normal is exactly
    // radial up to rounding — including the seam column, because its positions are shared.
    const BaseMesh m = knit::makeCylinder(opts(24, 5));
    const auto n = knit::vertexNormals(m.positions, m.faces);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const glm::dvec3 radial = glm::normalize(glm::dvec3(m.positions[i].x, 0.0, m.positions[i].z));
        EXPECT_GT(glm::dot(n[i], radial), 1.0 - 1e-12) << i;
        EXPECT_NEAR(n[i].y, 0.0, 1e-12) << i;
    }
    // The two UV copies of a seam vertex are one position, hence one normal: check through faces.
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (m.uvs[m.faceUvs[f][k]].x == 1.0) {
                EXPECT_EQ(m.faces[f][k] % 24, 0u);
            }
}

TEST(ProceduralMesh, sphereNormalsPointOutward) {
    const int nu = 16, nv = 12;
    const BaseMesh m = knit::makeSphere(opts(nu, nv));
    EXPECT_EQ(m.positions.size(), size_t(nu * (nv - 1) + 2));  // one position per pole
    const auto n = knit::vertexNormals(m.positions, m.faces);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(m.positions[i]), 0.1, 1e-15);
        // Within half a ring spacing of the radial direction.
        EXPECT_GT(glm::dot(n[i], glm::normalize(m.positions[i])), std::cos(0.5 * knit::util::kPi / nv)) << i;
    }
    // The poles' normals are the axis (symmetric fan): south pole at -y, north pole at +y.
    EXPECT_NEAR(n.front().y, -1.0, 1e-12);
    EXPECT_NEAR(n.back().y, 1.0, 1e-12);
}

TEST(ProceduralMesh, spherePoleTrianglesAreNotDegenerate) {
    const BaseMesh m = knit::makeSphere(opts(8, 4));
    const double minUvArea = 0.5 * (1.0 / 8) * (1.0 / 4);
    for (size_t f = 0; f < m.faces.size(); ++f) {
        EXPECT_NEAR(uvDet(m, f), 0.0, 1.0) << f;  // finite
        EXPECT_GE(0.5 * uvDet(m, f), minUvArea * (1 - 1e-12)) << f;
        EXPECT_GT(glm::length(faceNormal(m, f)), 1e-6) << f;
        const glm::uvec3 t = m.faces[f];
        EXPECT_TRUE(t.x != t.y && t.y != t.z && t.x != t.z) << f;
    }
}

TEST(ProceduralMesh, drapeHasNoDegenerateTriangles) {
    knit::ProceduralMeshOptions o = opts(40, 40);
    o.size = 0.6;
    const BaseMesh m = knit::makeDrape(o);
    // A height field (+y) over the regular grid: each 3D triangle is at least as large as its xz
    // projection, size²/(2·resU·resV).
    const double flatArea = o.size * o.size / (2.0 * o.resU * o.resV);
    for (size_t f = 0; f < m.faces.size(); ++f) {
        const glm::dvec3 n = faceNormal(m, f);
        EXPECT_GE(0.5 * glm::length(n), flatArea * (1 - 1e-9)) << f;
        EXPECT_NEAR(0.5 * n.y, flatArea, 1e-12) << f;
    }
}

TEST(ProceduralMesh, drapeLiesOnSphereCapAndFallsOff) {
    knit::ProceduralMeshOptions o = opts(30, 30);
    o.size = 0.6;
    const BaseMesh m = knit::makeDrape(o);
    const double R = o.size / 3, a = R * std::sin(knit::util::kPi / 4);
    size_t onCap = 0;
    for (const glm::dvec3& p : m.positions) {
        const double r = std::hypot(p.x, p.z);
        if (r <= a) {
            EXPECT_NEAR(glm::length(p), R, 1e-12);
            ++onCap;
        } else {
            EXPECT_LT(p.y, std::sqrt(R * R - a * a));    // below the contact circle
            EXPECT_GE(glm::length(p), R * (1 - 1e-12));  // never inside the sphere
        }
    }
    EXPECT_GT(onCap, 10u);
    // The corner is lower than the edge midpoint, which is lower than the top.
    EXPECT_LT(m.positions.front().y, m.positions[15].y);
    EXPECT_LT(m.positions[15].y, R);
}

TEST(ProceduralMesh, drapeNormalsVaryContinuously) {
    // The fall-off joins the cap with equal slope (C1): neighbouring vertex normals turn by about
    // curvature × spacing, far less than a kink would.
    knit::ProceduralMeshOptions o = opts(120, 120);
    const BaseMesh m = knit::makeDrape(o);
    const auto n = knit::vertexNormals(m.positions, m.faces);
    double maxTurn = 0;
    for (int j = 0; j <= o.resV; ++j)
        for (int i = 0; i < o.resU; ++i) {
            const size_t k = size_t(j * (o.resU + 1) + i);
            maxTurn = std::max(maxTurn, std::acos(std::min(1.0, glm::dot(n[k], n[k + 1]))));
        }
    const double spacing = o.size / o.resU, R = o.size / 3;
    EXPECT_LT(maxTurn, 1.5 * spacing / R);
}

TEST(ProceduralMesh, invalidOptionsAreRejected) {
    EXPECT_THROW(knit::makePlane(opts(0, 4)), knit::Error);
    EXPECT_THROW(knit::makeCylinder(opts(2, 4)), knit::Error);
    EXPECT_THROW(knit::makeSphere(opts(8, 1)), knit::Error);
    EXPECT_THROW(knit::makeDrape(opts(100000, 100000)), knit::Error);
    knit::ProceduralMeshOptions o;
    o.radius = -1;
    EXPECT_THROW(knit::makeSphere(o), knit::Error);
    o = {};
    o.size = std::nan("");
    EXPECT_THROW(knit::makePlane(o), knit::Error);
    o = {};
    o.height = 0;
    EXPECT_THROW(knit::makeCylinder(o), knit::Error);
}
