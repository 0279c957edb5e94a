// Tests for vertexNormals, uvToMetreScale, validateMesh and the built-in/file front door.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"
#include "util/math.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <functional>

using knit::BaseMesh;

namespace {

using knit::test::errorOf;

BaseMesh quad(double sx, double sy) {  // [0,sx] x [0,sy] with uv in [0,1]^2
    BaseMesh m;
    m.name = "quad";
    m.positions = {{0, 0, 0}, {sx, 0, 0}, {sx, sy, 0}, {0, sy, 0}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.faces = {{0, 1, 2}, {0, 2, 3}};
    m.faceUvs = m.faces;
    return m;
}

}  // namespace

TEST(BaseMesh, vertexNormalsAreAngleWeighted) {
    // Vertex 0 has a 90° corner in the plane z = 0 (normal +z) and a 45° corner in the plane
    // x = 0 (normal +x); both triangles have area 1/2, so area weighting would give (1, 0, 1).
    const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 1}};
    const std::vector<glm::uvec3> f = {{0, 1, 2}, {0, 2, 3}};
    const auto n = knit::vertexNormals(p, f);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(knit::util::kPi / 4, 0, knit::util::kPi / 2));
    EXPECT_NEAR(glm::length(n[0] - expected), 0.0, 1e-14);
    EXPECT_NEAR(glm::length(n[1] - glm::dvec3(0, 0, 1)), 0.0, 1e-14);
}

TEST(BaseMesh, isolatedAndDegenerateOnlyVerticesGetDefaultNormal) {
    const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {2, 0, 0}, {3, 0, 0}};
    // Face 1 is degenerate (collinear): it must neither add to vertex 1 nor give 4/5 a normal.
    const std::vector<glm::uvec3> f = {{0, 1, 2}, {1, 4, 5}};
    const auto n = knit::vertexNormals(p, f);
    EXPECT_EQ(n[3], glm::dvec3(0, 0, 1));  // isolated
    EXPECT_EQ(n[4], glm::dvec3(0, 0, 1));
    EXPECT_EQ(n[5], glm::dvec3(0, 0, 1));
    EXPECT_NEAR(glm::length(n[1] - glm::dvec3(0, 0, 1)), 0.0, 1e-15);
    // A flipped face points the other way: -z.
    const auto flipped = knit::vertexNormals(p, {{0, 2, 1}});
    EXPECT_NEAR(flipped[0].z, -1.0, 1e-15);
}

TEST(BaseMesh, planeUvScale) {
    for (double s : {0.25, 0.5, 3.0}) {
        knit::ProceduralMeshOptions o;
        o.size = s;
        o.resU = 5;
        o.resV = 3;
        const glm::dvec2 k = knit::uvToMetreScale(knit::makePlane(o));
        EXPECT_NEAR(k.x, s, 1e-12 * s);
        EXPECT_NEAR(k.y, s, 1e-12 * s);
    }
}

TEST(BaseMesh, uvScaleIsPerAxis) {
    // 2 m along u, 0.5 m along v: the axes must not be swapped or averaged.
    const glm::dvec2 k = knit::uvToMetreScale(quad(2.0, 0.5));
    EXPECT_NEAR(k.x, 2.0, 1e-14);
    EXPECT_NEAR(k.y, 0.5, 1e-14);
}

TEST(BaseMesh, cylinderUvScaleIsChordPerimeterAndHeight) {
    knit::ProceduralMeshOptions o;
    o.resU = 12;
    o.resV = 4;
    const glm::dvec2 k = knit::uvToMetreScale(knit::makeCylinder(o));
    EXPECT_NEAR(k.x, o.resU * 2 * o.radius * std::sin(knit::util::kPi / o.resU), 1e-12);  // polygon perimeter
    EXPECT_NEAR(k.y, o.height, 1e-12);
}

TEST(BaseMesh, uvScaleIgnoresDegenerateUvTriangles) {
    BaseMesh m = quad(2.0, 0.5);
    m.positions.push_back({9, 9, 9});
    m.faces.push_back({0, 1, 4});    // big 3D triangle...
    m.faceUvs.push_back({0, 1, 1});  // ...with a collapsed UV triangle
    const glm::dvec2 k = knit::uvToMetreScale(m);
    EXPECT_NEAR(k.x, 2.0, 1e-14);
    EXPECT_NEAR(k.y, 0.5, 1e-14);
    BaseMesh allDegenerate = quad(1, 1);
    allDegenerate.uvs = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
    EXPECT_THROW(knit::uvToMetreScale(allDegenerate), knit::Error);
}

TEST(BaseMesh, validateMeshNamesTheBadElement) {
    EXPECT_NO_THROW(knit::validateMesh(quad(1, 1)));
    BaseMesh m = quad(1, 1);
    m.faceUvs[1].y = 99;
    EXPECT_EQ(errorOf([&] { knit::validateMesh(m); }), "quad: face 1 references uv 99 but the mesh has 4 uvs");
    m = quad(1, 1);
    m.faces[0].z = 4;
    EXPECT_EQ(errorOf([&] { knit::validateMesh(m); }),
              "quad: face 0 references position 4 but the mesh has 4 positions");
    m = quad(1, 1);
    m.faceUvs.pop_back();
    EXPECT_NE(errorOf([&] { knit::validateMesh(m); }).find("2 faces but 1 UV faces"), std::string::npos);
    m = quad(1, 1);
    m.uvs[2].x = std::nan("");
    EXPECT_NE(errorOf([&] { knit::validateMesh(m); }).find("uv 2 is not finite"), std::string::npos);
    m = quad(1, 1);
    m.positions[3].z = INFINITY;
    EXPECT_NE(errorOf([&] { knit::validateMesh(m); }).find("position 3 is not finite"), std::string::npos);
    m = quad(1, 1);
    m.faces.clear();
    m.faceUvs.clear();
    EXPECT_NE(errorOf([&] { knit::validateMesh(m); }).find("no faces"), std::string::npos);
}

TEST(BaseMesh, unknownBuiltinNameListsKnownNames) {
    const std::string msg = errorOf([] { knit::builtinMesh("torus"); });
    EXPECT_NE(msg.find("torus"), std::string::npos);
    EXPECT_NE(msg.find("plane, cylinder, sphere, drape"), std::string::npos) << msg;
}

TEST(BaseMesh, loadMeshFileOrNameTellsFilesFromBuiltins) {
    knit::ProceduralMeshOptions o;
    o.resU = 3;
    o.resV = 2;
    EXPECT_EQ(knit::loadMeshFileOrName("cylinder", o).faces.size(), 12u);
    knit::test::TempDir dir;
    const std::string tri = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    EXPECT_EQ(knit::loadMeshFileOrName(tri).name, tri);
    // A mesh extension means a file, even when missing; anything else unknown lists both options.
    EXPECT_NE(errorOf([&] { knit::loadMeshFileOrName(dir.file("plane.obj")); }).find("no such file"),
              std::string::npos);
    const std::string msg = errorOf([] { knit::loadMeshFileOrName("no_such_mesh"); });
    EXPECT_NE(msg.find("neither a mesh file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("plane, cylinder, sphere, drape"), std::string::npos) << msg;
}

namespace knit {
namespace {

// Two of a plane's triangles: only their corners and UVs, renumbered in order of first use, each
// triangle's corners and UVs where they were.
TEST(MeshSubset, keepsOnlyTheVerticesAndUvsOfTheChosenTriangles) {
    ProceduralMeshOptions o;
    o.resU = o.resV = 3;
    const BaseMesh plane = makePlane(o);
    const std::vector<uint32_t> faces{7, 2};
    const BaseMesh sub = meshSubset(plane, faces, " (part)");
    EXPECT_EQ(sub.name, plane.name + " (part)");
    ASSERT_EQ(sub.faces.size(), 2u);
    ASSERT_EQ(sub.faceUvs.size(), 2u);
    EXPECT_LE(sub.positions.size(), 6u);
    EXPECT_LE(sub.uvs.size(), 6u);
    EXPECT_EQ(sub.faces[0], glm::uvec3(0, 1, 2));  // first use numbers the corners 0, 1, 2
    for (size_t i = 0; i < faces.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(sub.positions[sub.faces[i][k]], plane.positions[plane.faces[faces[i]][k]]);
            EXPECT_EQ(sub.uvs[sub.faceUvs[i][k]], plane.uvs[plane.faceUvs[faces[i]][k]]);
        }
    EXPECT_NO_THROW(validateMesh(sub));
    EXPECT_TRUE(meshSubset(plane, {}).faces.empty());
    EXPECT_THROW(meshSubset(plane, {uint32_t(plane.faces.size())}), Error);
}

}  // namespace
}  // namespace knit
