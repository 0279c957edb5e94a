// Tests for loadMesh (OBJ / PLY / OFF, libknit's own readers): seams, welding, precision, and the
// malformed inputs OpenMesh's readers (used before) would accept silently.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"
#include "util/math.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <sstream>

using knit::BaseMesh;
using knit::test::TempDir;

namespace {

using knit::test::errorOf;

// A ring of 4 side quads (a square prism, radius 1, z in {0, 0.1}) with a UV seam at u = 0/1:
// 8 positions, 10 UVs (u = i/4, v = j).
const double kRingZ[2] = {0.0, 0.1};
const double kRingXY[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};

std::string ringObj() {
    std::ostringstream s;
    s.precision(17);
    s << "# square prism ring with a UV seam\n";
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) s << "v " << kRingXY[i][0] << " " << kRingXY[i][1] << " " << kRingZ[j] << "\n";
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i <= 4; ++i) s << "vt " << i / 4.0 << " " << j << "\n";
    for (int i = 0; i < 4; ++i) {
        auto corner = [&](int ci, int cj) {
            return std::to_string(cj * 4 + ci % 4 + 1) + "/" + std::to_string(cj * 5 + ci + 1);
        };
        s << "f " << corner(i, 0) << " " << corner(i + 1, 0) << " " << corner(i + 1, 1) << " " << corner(i, 1) << "\n";
    }
    return s.str();
}

// The same ring as a PLY that duplicates the seam column (10 vertices with per-vertex u,v).
std::string ringPly(const char* uName = "u", const char* vName = "v") {
    std::ostringstream s;
    s.precision(17);
    s << "ply\nformat ascii 1.0\ncomment ring with duplicated seam vertices\nelement vertex 10\n"
      << "property float x\nproperty float y\nproperty float z\nproperty float " << uName << "\nproperty float "
      << vName << "\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i <= 4; ++i)
            s << kRingXY[i % 4][0] << " " << kRingXY[i % 4][1] << " " << kRingZ[j] << " " << i / 4.0 << " " << j
              << "\n";
    for (int i = 0; i < 4; ++i) s << "4 " << i << " " << i + 1 << " " << 5 + i + 1 << " " << 5 + i << "\n";
    return s.str();
}

template <class T>
void putBE(std::string& out, T value) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    for (size_t i = 0; i < sizeof(T); ++i) out.push_back(char(b[sizeof(T) - 1 - i]));
}

}  // namespace

TEST(MeshIo, objWithSeamSharesPositions) {
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("ring.obj", ringObj()));
    ASSERT_EQ(m.positions.size(), 8u);
    ASSERT_EQ(m.uvs.size(), 10u);
    ASSERT_EQ(m.faces.size(), 8u);  // 4 quads, fan-triangulated
    // Every corner whose position is the seam column (x = 1, y = 0) has u = 0 or u = 1, and both
    // occur: one position, two UV vertices.
    bool sawU0 = false, sawU1 = false;
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = m.positions[m.faces[f][k]];
            const glm::dvec2 uv = m.uvs[m.faceUvs[f][k]];
            if (p.x == 1.0 && p.y == 0.0) {
                EXPECT_TRUE(uv.x == 0.0 || uv.x == 1.0);
                sawU0 |= uv.x == 0.0;
                sawU1 |= uv.x == 1.0;
            }
            // The UV corner belongs to the right position: u = i/4 <-> angle i·90°.
            EXPECT_NEAR(p.x, std::cos(uv.x * 2 * knit::util::kPi), 1e-12);
            EXPECT_NEAR(p.y, std::sin(uv.x * 2 * knit::util::kPi), 1e-12);
        }
    EXPECT_TRUE(sawU0 && sawU1);
    // The 3D topology is closed around the seam, so the seam normal is radial.
    const auto n = knit::vertexNormals(m.positions, m.faces);
    EXPECT_NEAR(n[0].x, 1.0, 1e-12);
    EXPECT_NEAR(n[0].y, 0.0, 1e-12);
}

TEST(MeshIo, objKeepsDoublePrecisionPositions) {
    // OpenMesh's OBJ reader stores float32; 0.1 must come back as the double 0.1.
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("ring.obj", ringObj()));
    EXPECT_EQ(m.positions[4].z, 0.1);
    EXPECT_NE(double(float(0.1)), 0.1);
}

TEST(MeshIo, plyWithDuplicatedSeamVerticesIsWelded) {
    TempDir dir;
    const BaseMesh obj = knit::loadMesh(dir.write("ring.obj", ringObj()));
    const BaseMesh ply = knit::loadMesh(dir.write("ring.ply", ringPly()));
    ASSERT_EQ(ply.positions.size(), 8u);  // 10 file vertices, seam column welded
    EXPECT_EQ(ply.uvs, obj.uvs);
    EXPECT_EQ(ply.faces, obj.faces);
    EXPECT_EQ(ply.faceUvs, obj.faceUvs);
    const auto nObj = knit::vertexNormals(obj.positions, obj.faces);
    const auto nPly = knit::vertexNormals(ply.positions, ply.faces);
    for (size_t i = 0; i < nObj.size(); ++i) EXPECT_NEAR(glm::length(nObj[i] - nPly[i]), 0.0, 1e-6) << i;
    // Without welding the seam stays open: 10 positions.
    knit::MeshLoadOptions noWeld;
    noWeld.weldEqualPositions = false;
    EXPECT_EQ(knit::loadMesh(dir.file("ring.ply"), noWeld).positions.size(), 10u);
}

TEST(MeshIo, plyStAndTextureUvPropertiesAreRead) {
    TempDir dir;
    const BaseMesh ref = knit::loadMesh(dir.write("uv.ply", ringPly("u", "v")));
    for (auto names :
         {std::pair<const char*, const char*>{"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}) {
        const BaseMesh m =
            knit::loadMesh(dir.write(std::string(names.first) + ".ply", ringPly(names.first, names.second)));
        EXPECT_EQ(m.uvs, ref.uvs) << names.first;
        EXPECT_EQ(m.faceUvs, ref.faceUvs) << names.first;
    }
}

TEST(MeshIo, binaryBigEndianPlyWithDoubleTextureUvLoads) {
    std::string s = "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                    "property double z\nproperty double texture_u\nproperty double texture_v\nelement face 1\n"
                    "property list uchar uint vertex_indices\nend_header\n";
    const double v[4][5] = {{0, 0, 0, 0, 0}, {2, 0, 0, 1, 0}, {2, 1, 0, 1, 1}, {0, 1, 0, 0, 1}};
    for (const auto& row : v)
        for (double c : row) putBE(s, c);
    s.push_back(char(4));
    for (uint32_t i : {0u, 1u, 2u, 3u}) putBE(s, i);
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("quad.ply", s));
    ASSERT_EQ(m.faces.size(), 2u);
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.uvs[m.faceUvs[0][1]], glm::dvec2(1, 0));
    EXPECT_EQ(m.positions[m.faces[0][1]], glm::dvec3(2, 0, 0));
    const glm::dvec2 scale = knit::uvToMetreScale(m);
    EXPECT_NEAR(scale.x, 2.0, 1e-12);
    EXPECT_NEAR(scale.y, 1.0, 1e-12);
}

// PLY is read in one pass by libknit (no longer by OpenMesh's reader after the checking walk); a
// file loads exactly as OpenMesh delivered it.
TEST(MeshIo, plyLoadsAsOpenMeshDeliveredIt) {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\n";
    const std::string faces = "element face 2\nproperty list uchar int vertex_indices\n";
    const std::string verts = "0 0 0.1 0 0.1\n1 0 0.1 1 0\n1 1 0.1 1 1\n0 1 0.1 0 1\n";
    TempDir dir;
    // Positions and u,v in float32; texture_u,texture_v as declared (double here).
    const BaseMesh f = knit::loadMesh(dir.write("f.ply", head + "property float u\nproperty float v\n" + faces +
                                                             "end_header\n" + verts + "3 0 1 2\n3 0 2 3\n"));
    EXPECT_EQ(f.positions[0].z, double(0.1f));
    EXPECT_EQ(f.uvs[f.faceUvs[0][0]].y, double(0.1f));
    const BaseMesh d =
        knit::loadMesh(dir.write("d.ply", head + "property double texture_u\nproperty double texture_v\n" + faces +
                                              "end_header\n" + verts + "3 0 1 2\n3 0 2 3\n"));
    EXPECT_EQ(d.uvs[d.faceUvs[0][0]].y, 0.1);
    // Only u: v is 0. The last index of the last face is read as far as it is an integer ("3.0"
    // is 3), and elements after 'face' are only checked.
    const BaseMesh u = knit::loadMesh(dir.write("u.ply", head + "property float u\nproperty float q\n" + faces +
                                                             "element edge 1\nproperty list uchar int e\nend_header\n" +
                                                             verts + "3 0 1 2\n3 0 2 3.0\n2 0 1\n"));
    ASSERT_EQ(u.faces.size(), 2u);
    EXPECT_EQ(u.faces, f.faces);
    EXPECT_EQ(u.uvs[u.faceUvs[0][2]], glm::dvec2(1, 0));
}

TEST(MeshIo, plyLayoutsOpenMeshMisreadAreRefusedNamingTheLine) {
    const std::string vertex = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "property float u\nproperty float v\n";
    const std::string face = "element face 2\nproperty list uchar int vertex_indices\n";
    const std::string data = "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n";
    TempDir dir;
    auto error = [&](const std::string& name, const std::string& text) {
        return errorOf([&] { knit::loadMesh(dir.write(name, text)); });
    };
    // A token OpenMesh read in part ("2.0" as an index: 2, then ".0" as the next value).
    EXPECT_NE(
        error("part.ply", "ply\nformat ascii 1.0\n" + vertex + face + "end_header\n" + data + "3 0 1 2.0\n3 0 1 2\n")
            .find("part.ply:15: '2.0' in property 'vertex_indices' of element 'face' must be a plain integer"),
        std::string::npos);
    // A header line before the format line (OpenMesh took the words after 'ply' as the format).
    EXPECT_NE(error("fmt.ply",
                    "ply\ncomment c\nformat ascii 1.0\n" + vertex + face + "end_header\n" + data + "3 0 1 2\n3 0 2 1\n")
                  .find("fmt.ply:3: the format line must come right after the 'ply' line"),
              std::string::npos);
    // A non-empty list OpenMesh skipped as one value.
    EXPECT_NE(error("list.ply", "ply\nformat ascii 1.0\n" + vertex + "property list uchar int l\n" + face +
                                    "end_header\n0 0 0 0 0 1 7\n1 0 0 1 0 0\n0 1 0 0 1 0\n3 0 1 2\n3 0 2 1\n")
                  .find("list.ply:13: list 'l' of element 'vertex' must be empty"),
              std::string::npos);
    // A list count type OpenMesh did not know.
    EXPECT_NE(error("count.ply", "ply\nformat ascii 1.0\n" + vertex +
                                     "element face 1\nproperty list ushort int vertex_indices\nend_header\n" + data +
                                     "3 0 1 2\n")
                  .find("count type 'ushort'"),
              std::string::npos);
    // Binary: a comment right before end_header (OpenMesh started the data one byte late).
    std::string bin = "ply\nformat binary_big_endian 1.0\n" + vertex +
                      "element face 1\nproperty list uchar int vertex_indices\ncomment c\nend_header\n";
    for (float c : {0.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f}) putBE(bin, c);
    bin.push_back(char(3));
    for (int32_t i : {0, 1, 2}) putBE(bin, i);
    EXPECT_NE(error("bin.ply", bin).find("'end_header' must directly follow the last header line"), std::string::npos);
}

TEST(MeshIo, offLoads) {
    TempDir dir;
    // A quad and a triangle, texture coordinates per vertex (STOFF).
    const BaseMesh m = knit::loadMesh(dir.write("m.off", "STOFF\n# comment\n5 2 0\n"
                                                         "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n2 0.5 0 1 0.5\n"
                                                         "4 0 1 2 3\n3 1 4 2\n"));
    ASSERT_EQ(m.faces.size(), 3u);
    EXPECT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.faces[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(m.faces[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(m.uvs[m.faceUvs[2][1]], glm::dvec2(1, 0.5));
}

TEST(MeshIo, offWithCommentsAndCountsOnHeaderLineLoads) {
    // OpenMesh's OFF reader knows neither: it read garbage counts and looped over millions of
    // empty faces. The loader hands it a cleaned copy.
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("c.off", "STOFF 4 2 0 # counts on the header line\n# a comment\n"
                                                         "0 0 0 0 0\n1 0 0 1 0 # trailing comment\n1 1 0 1 1\n"
                                                         "\n0 1 0 0 1\n3 0 1 2\n3 0 2 3\n"));
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.faces[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(m.uvs[m.faceUvs[1][1]], glm::dvec2(1, 1));
}

TEST(MeshIo, declaredCountsBeyondTheDataAreRejected) {
    TempDir dir;
    const std::string off = dir.write("huge.off", "STOFF\n3 2000000000 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(off); }).find("truncated"), std::string::npos);
    std::string ply = ringPly();
    ply.replace(ply.find("element face 4"), 14, "element face 4000000000");
    EXPECT_NE(errorOf([&] { knit::loadMesh(dir.write("huge.ply", ply)); }).find("truncated"), std::string::npos);
    std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nproperty float u\nproperty float v\nelement face 2000000000\n"
                      "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 15; ++i) bin.append(4, '\0');
    EXPECT_THROW(knit::loadMesh(dir.write("huge_bin.ply", bin)), knit::Error);
}

TEST(MeshIo, binaryOffIsRejected) {
    TempDir dir;
    const std::string p = dir.write("b.off", std::string("OFF BINARY\n") + std::string(12, '\0'));
    EXPECT_NE(errorOf([&] { knit::loadMesh(p); }).find("binary OFF is not supported"), std::string::npos);
}

TEST(MeshIo, crlfLineEndingsLoad) {
    TempDir dir;
    auto crlf = [](std::string s) {
        for (size_t i = s.find('\n'); i != std::string::npos; i = s.find('\n', i + 2)) s.insert(i, 1, '\r');
        return s;
    };
    const BaseMesh obj = knit::loadMesh(dir.write("ring.obj", crlf(ringObj())));
    const BaseMesh ply = knit::loadMesh(dir.write("ring.ply", crlf(ringPly())));
    EXPECT_EQ(obj.faces.size(), 8u);
    EXPECT_EQ(ply.faces, obj.faces);
    EXPECT_EQ(ply.faceUvs, obj.faceUvs);
    const BaseMesh off =
        knit::loadMesh(dir.write("q.off", crlf("STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n")));
    EXPECT_EQ(off.uvs[off.faceUvs[0][2]], glm::dvec2(0, 1));
}

TEST(MeshIo, offWithoutTexcoordsIsRejected) {
    TempDir dir;
    const std::string p = dir.write("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(p); }).find("no texture coordinates"), std::string::npos);
}

TEST(MeshIo, offVertexLayoutFollowsTheHeader) {
    // Normals (N) and colours (C, integer or float RGB[A]) come before u v on a vertex line.
    TempDir dir;
    const char* faces = "4 0 1 2 3\n3 0 2 3\n";
    const std::string plain = std::string("STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0.5 1 1\n0 1 0 0 1\n") + faces;
    const std::string normalsAndColours = std::string("STCNOFF\n4 2 0\n0 0 0 0 0 1 255 0 0 0 0\n") +
                                          "1 0 0 0 0 1 0.1 0.2 0.3 0.4 1 0\n1 1 0.5 0 0 1 1 2 3 1 1\n" +
                                          "0 1 0 0 0 1 0 0 0 255 0 1\n" + faces;
    const BaseMesh a = knit::loadMesh(dir.write("plain.off", plain));
    const BaseMesh b = knit::loadMesh(dir.write("nc.off", normalsAndColours));
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_EQ(a.faceUvs, b.faceUvs);
    // A vertex line without its u v is refused naming the line (OpenMesh, used before, kept the
    // previous vertex's texture coordinates, or uninitialized ones for the first vertex).
    const std::string shortLine = dir.write("short.off", "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0\n1 1 0.5 1 1\n"
                                                         "0 1 0 0 1\n4 0 1 2 3\n3 0 2 3\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(shortLine); }).find("short.off:4: a vertex line needs at least 5 numbers"),
              std::string::npos);
    // The header starts the first line.
    const std::string indented = dir.write("indented.off", " " + plain);
    EXPECT_NE(errorOf([&] { knit::loadMesh(indented); }).find("indented.off:1: not an OFF file"), std::string::npos);
}

TEST(MeshIo, truncatedOffIsRejected) {
    // OpenMesh repeats the last face for missing face lines and reports success.
    TempDir dir;
    const std::string p = dir.write("m.off", "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n");
    EXPECT_THROW(knit::loadMesh(p), knit::Error);
}

TEST(MeshIo, polygonIsFanTriangulatedWithMatchingUvs) {
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("pent.obj", "v 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 1.5 0\nv -0.5 1 0\n"
                                                            "vt 0 0\nvt 1 0\nvt 1 0.6\nvt 0.5 1\nvt 0 0.6\n"
                                                            "f 1/1 2/2 3/3 4/4 5/5\n"));
    ASSERT_EQ(m.faces.size(), 3u);
    for (size_t f = 0; f < 3; ++f) {
        EXPECT_EQ(m.faces[f], glm::uvec3(0, f + 1, f + 2));
        EXPECT_EQ(m.faceUvs[f], glm::uvec3(0, f + 1, f + 2));
    }
}

TEST(MeshIo, objOppositelyOrientedNeighbourKeepsItsUvs) {
    // The second face runs the shared edge in the same direction (non-manifold for a halfedge
    // mesh: OpenMesh's ImporterT would duplicate its vertices and start its texcoords at the wrong
    // corner). Here every corner keeps its own vt and the positions stay shared.
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("flip.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                                            "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                                            "f 1/1 2/2 3/3\nf 2/2 3/3 4/4\n"));
    ASSERT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.faces.size(), 2u);
    for (size_t f = 0; f < 2; ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = m.positions[m.faces[f][k]];
            EXPECT_EQ(m.uvs[m.faceUvs[f][k]], glm::dvec2(p.x, p.y));
        }
}

TEST(MeshIo, uppercaseExtensionAndNegativeObjIndicesLoad) {
    TempDir dir;
    const BaseMesh m = knit::loadMesh(dir.write("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                                           "f -3/-3 -2/-2 -1/-1\n"));
    ASSERT_EQ(m.faces.size(), 1u);
    EXPECT_EQ(m.positions[m.faces[0][1]], glm::dvec3(1, 0, 0));
    EXPECT_EQ(m.uvs[m.faceUvs[0][2]], glm::dvec2(0, 1));
}

TEST(MeshIo, meshWithoutUvsIsRejected) {
    TempDir dir;
    const std::string obj = dir.write("nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string msg = errorOf([&] { knit::loadMesh(obj); });
    EXPECT_NE(msg.find("nouv.obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no texture coordinates (vt)"), std::string::npos) << msg;
    const std::string ply = dir.write("nouv.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                                  "property float y\nproperty float z\nelement face 1\n"
                                                  "property list uchar int vertex_indices\nend_header\n"
                                                  "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(ply); }).find("no per-vertex texture coordinates"), std::string::npos);
}

TEST(MeshIo, objHexadecimalNumbersAreRefusedAtTheirLine) {
    // strtod reads "0x1p3" as 8; an OBJ reader (OpenMesh's, used before) reads the 0 and fails
    // on the rest, so such a file is refused naming the line instead of loading either value.
    TempDir dir;
    const std::string v = dir.write("hexv.obj", "v 0 0 0\nv 0x1p3 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(v); }).find("hexv.obj:2: vertex position is not three finite numbers"),
              std::string::npos);
    const std::string vt = dir.write("hexvt.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 -0X1\nf 1/1 2/1 3/1\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(vt); }).find("hexvt.obj:4: texture coordinate (vt) is not two finite"),
              std::string::npos);
}

TEST(MeshIo, objFaceWithoutVtIsRejected) {
    TempDir dir;
    const std::string p = dir.write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                                 "f 1/1 2/2 3/3\nf 2 4 3\n");
    const std::string msg = errorOf([&] { knit::loadMesh(p); });
    EXPECT_NE(msg.find("mixed.obj:9:"), std::string::npos) << msg;
}

TEST(MeshIo, emptyMeshIsRejected) {
    TempDir dir;
    const std::string noFaces = dir.write("pts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(noFaces); }).find("no faces"), std::string::npos);
    const std::string empty = dir.write("empty.obj", "");
    EXPECT_NE(errorOf([&] { knit::loadMesh(empty); }).find("no faces"), std::string::npos);
    const std::string emptyPly = dir.write("empty.ply", "");
    EXPECT_THROW(knit::loadMesh(emptyPly), knit::Error);
    const std::string noFacePly =
        dir.write("nf.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                            "property float y\nproperty float z\nproperty float u\n"
                            "property float v\nelement face 0\n"
                            "property list uchar int vertex_indices\nend_header\n0 0 0 0 0\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(noFacePly); }).find("no faces"), std::string::npos);
}

TEST(MeshIo, nanPositionIsRejected) {
    TempDir dir;
    // OBJ: OpenMesh would skip the line and shift every later vertex index.
    const std::string obj = dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    const std::string msg = errorOf([&] { knit::loadMesh(obj); });
    EXPECT_NE(msg.find("nan.obj:2:"), std::string::npos) << msg;
    EXPECT_THROW(knit::loadMesh(dir.write("inf.obj", "v 0 0 0\nv 1e400 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\n")),
                 knit::Error);
    EXPECT_THROW(knit::loadMesh(dir.write("nanvt.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt nan 0\nf 1/1 2/1 3/1\n")),
                 knit::Error);
    // ASCII PLY: OpenMesh would read zeros and empty faces and report success.
    std::string ply = ringPly();
    ply.replace(ply.find("\n0 1 0 0.25 0\n"), 14, "\n0 nan 0 0.25 0\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(dir.write("nan.ply", ply)); }).find("'nan' is not a finite number"),
              std::string::npos);
    // Binary PLY: the value arrives as inf.
    std::string bin = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                      "property double z\nproperty float u\nproperty float v\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n";
    const double pos[3][3] = {{0, 0, 0}, {1, 0, HUGE_VAL}, {0, 1, 0}};
    for (int i = 0; i < 3; ++i) {
        for (double c : pos[i]) putBE(bin, c);
        putBE(bin, float(pos[i][0]));
        putBE(bin, float(pos[i][1]));
    }
    bin.push_back(char(3));
    for (int32_t i : {0, 1, 2}) putBE(bin, i);
    EXPECT_NE(errorOf([&] { knit::loadMesh(dir.write("inf.ply", bin)); }).find("non-finite position"),
              std::string::npos);
    // OFF: OpenMesh would produce garbage face indices.
    EXPECT_THROW(knit::loadMesh(dir.write("nan.off", "STOFF\n3 1 0\n0 0 0 0 0\n1 nan 0 1 0\n0 1 0 0 1\n3 0 1 2\n")),
                 knit::Error);
}

TEST(MeshIo, faceIndexOutOfRangeIsRejected) {
    TempDir dir;
    const std::string obj = dir.write("oor.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 9/3\n");
    const std::string msg = errorOf([&] { knit::loadMesh(obj); });
    EXPECT_NE(msg.find("oor.obj:7: face references vertex 9 but the file has 3 vertices"), std::string::npos) << msg;
    const std::string vt = dir.write("oorvt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/7\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(vt); }).find("texture coordinate 7"), std::string::npos);
    std::string ply = ringPly();
    ply.replace(ply.find("\n4 3 4 9 8\n"), 11, "\n4 3 4 99 8\n");
    const std::string plyMsg = errorOf([&] { knit::loadMesh(dir.write("oor.ply", ply)); });
    EXPECT_NE(plyMsg.find("face 3 references vertex 99 but the file has 10 vertices"), std::string::npos) << plyMsg;
    EXPECT_THROW(knit::loadMesh(dir.write("oor.off", "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 7\n")),
                 knit::Error);
}

TEST(MeshIo, repeatedFaceVertexIsRejected) {
    TempDir dir;
    const std::string obj = dir.write("rep.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 2/1 3/1\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(obj); }).find("rep.obj:5: face uses vertex 2 twice"), std::string::npos);
}

TEST(MeshIo, missingFileIsRejected) {
    TempDir dir;
    const std::string p = dir.file("absent.obj");
    EXPECT_EQ(errorOf([&] { knit::loadMesh(p); }), p + ": no such file");
}

TEST(MeshIo, directoryIsRejected) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("folder.obj"));
    const std::string msg = errorOf([&] { knit::loadMesh(dir.file("folder.obj")); });
    EXPECT_NE(msg.find("is a directory"), std::string::npos) << msg;
}

TEST(MeshIo, unknownExtensionIsRejected) {
    TempDir dir;
    const std::string p = dir.write("mesh.stl", "solid x\nendsolid x\n");
    EXPECT_NE(errorOf([&] { knit::loadMesh(p); }).find("unknown mesh file extension '.stl'"), std::string::npos);
}

namespace {

// The L-shaped hexagon [0,2]x[0,1] U [0,1]x[0,2] (area 3), listed from the corner after the
// reflex one: its fan from the first corner covers the notch (1,2]x(1,2].
const double kLShape[6][2] = {{1, 2}, {0, 2}, {0, 0}, {2, 0}, {2, 1}, {1, 1}};

bool insideLShape(glm::dvec2 p) {
    const double e = 1e-12;
    const bool lower = p.x >= -e && p.x <= 2 + e && p.y >= -e && p.y <= 1 + e;
    const bool left = p.x >= -e && p.x <= 1 + e && p.y >= -e && p.y <= 2 + e;
    return lower || left;
}

// Signed area (counter-clockwise positive, seen from +z) of every triangle; fails the test if a
// sample point of one lies outside the L.
std::vector<double> lShapeTriangleAreas(const BaseMesh& m) {
    std::vector<double> areas;
    for (const glm::uvec3& f : m.faces) {
        const glm::dvec2 a(m.positions[f.x]), b(m.positions[f.y]), c(m.positions[f.z]);
        areas.push_back(0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)));
        for (int i = 0; i <= 8; ++i)
            for (int j = 0; i + j <= 8; ++j) {
                const glm::dvec2 p = a + (b - a) * (i / 8.0) + (c - a) * (j / 8.0);
                EXPECT_TRUE(insideLShape(p)) << "triangle sample (" << p.x << ", " << p.y << ") outside the L";
            }
    }
    return areas;
}

std::string lShapeObj() {
    std::ostringstream s;
    for (const auto& c : kLShape) s << "v " << c[0] << " " << c[1] << " 0\n";
    for (const auto& c : kLShape) s << "vt " << c[0] / 2 << " " << c[1] / 2 << "\n";
    s << "f 1/1 2/2 3/3 4/4 5/5 6/6\n";
    return s.str();
}

}  // namespace

TEST(MeshIo, concaveLShapedHexagonIsTriangulatedInsideItsOutline) {
    TempDir dir;
    for (const std::string& name : {std::string("l.obj"), std::string("l.off")}) {
        std::string text = lShapeObj();
        if (name == "l.off") {
            std::ostringstream s;
            s << "STOFF\n6 1 0\n";
            for (const auto& c : kLShape) s << c[0] << " " << c[1] << " 0 " << c[0] / 2 << " " << c[1] / 2 << "\n";
            s << "6 0 1 2 3 4 5\n";
            text = s.str();
        }
        const BaseMesh m = knit::loadMesh(dir.write(name, text));
        ASSERT_EQ(m.faces.size(), 4u) << name;
        const std::vector<double> areas = lShapeTriangleAreas(m);
        double total = 0;
        for (double a : areas) {
            EXPECT_GT(a, 0) << name << ": a triangle is wound against the polygon";
            total += a;
        }
        EXPECT_NEAR(total, 3.0, 1e-12) << name;
        // Each corner keeps its own UV (uv = position / 2).
        for (size_t f = 0; f < m.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) EXPECT_EQ(m.uvs[m.faceUvs[f][k]], glm::dvec2(m.positions[m.faces[f][k]]) / 2.0);
    }
}

TEST(MeshIo, selfCrossingAndAreaLessPolygonsAreRefusedNamingFaceAndLine) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 3 0 0\nv 3 2 0\nv 1 -1 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\n";
    // Edge (3,2)-(1,-1) crosses edge (0,0)-(3,0).
    const std::string crossing =
        errorOf([&] { knit::loadMesh(dir.write("cross.obj", head + "f 1/1 2/2 3/3\nf 1/1 2/2 3/3 4/1 5/3\n")); });
    EXPECT_NE(crossing.find("cross.obj: face 1 (line 10) crosses or touches itself"), std::string::npos) << crossing;
    const std::string flat = errorOf([&] {
        knit::loadMesh(dir.write("flat.off", "STOFF\n4 1 0\n0 0 0 0 0\n1 0 0 0 0\n2 0 0 0 0\n3 0 0 0 0\n4 0 1 2 3\n"));
    });
    EXPECT_NE(flat.find("flat.off: face 0 (line 7) has no area"), std::string::npos) << flat;
}
