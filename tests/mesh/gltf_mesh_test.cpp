// glTF 2.0 base meshes: files are assembled byte by byte (gltf_builder.hpp: JSON with a base64
// buffer, GLB container, external .bin), independently of the glTF reader under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"
#include "mesh/gltf_builder.hpp"
#include "mesh/mesh_test_util.hpp"

namespace {

using knit_test::errorOf;
using knit_test::GltfBuilder;

using nlohmann::json;

// The built-in cylinder written as glTF: one vertex per (position, uv) pair as glTF requires
// (the seam's positions twice), v stored flipped (glTF's texture origin is top-left).
GltfBuilder cylinderGltf(knit::BaseMesh& mesh) {
    knit::ProceduralMeshOptions o;
    o.resU = 12;
    o.resV = 5;
    mesh = knit::makeCylinder(o);
    std::vector<float> pos, uv;
    std::vector<uint32_t> idx;
    for (size_t f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = mesh.positions[mesh.faces[f][k]];
            const glm::dvec2 t = mesh.uvs[mesh.faceUvs[f][k]];
            pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
            uv.insert(uv.end(), {float(t.x), float(1.0 - t.y)});
            idx.push_back(uint32_t(idx.size()));
        }
    GltfBuilder g;
    g.doc["nodes"] = json::array({{{"mesh", g.mesh(pos, uv, idx)}}});
    g.doc["scenes"] = json::array({{{"nodes", {0}}}});
    g.doc["scene"] = 0;
    return g;
}

// The quad (0,0)-(1,0)-(1,1)-(0,1) in z = 0 with uv = xy (glTF v flipped).
const std::vector<float> kQuadPos{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<float> kQuadUv{0, 1, 1, 1, 1, 0, 0, 0};

// A document with the quad as mesh 0 and one node; `edit` changes it before it is written.
std::string quadFile(const std::function<void(GltfBuilder&)>& edit, bool binary = false) {
    GltfBuilder g;
    g.mesh(kQuadPos, kQuadUv, {0, 1, 2, 0, 2, 3});
    g.doc["nodes"] = json::array({{{"mesh", 0}}});
    g.doc["scenes"] = json::array({{{"nodes", {0}}}});
    edit(g);
    return binary ? g.glb() : g.gltf();
}

TEST(GltfMesh, cylinderSeamIsWeldedAndUvsFlipBack) {
    knit::BaseMesh ref;
    const GltfBuilder g = cylinderGltf(ref);
    for (const std::string& bytes : {g.gltf(), g.glb()}) {
        const knit::BaseMesh m = knit::parseGltfMesh(bytes, "cylinder.gltf", "");
        // One 3D vertex per distinct position: the seam (duplicated in the file) is welded.
        EXPECT_EQ(m.positions.size(), ref.positions.size());
        EXPECT_EQ(m.uvs.size(), ref.uvs.size());
        ASSERT_EQ(m.faceCount(), ref.faceCount());
        double worstP = 0, worstUv = 0;
        for (size_t f = 0; f < m.faceCount(); ++f)
            for (int k = 0; k < 3; ++k) {
                worstP = std::max(worstP, glm::distance(m.positions[m.faces[f][k]], ref.positions[ref.faces[f][k]]));
                worstUv = std::max(worstUv, glm::distance(m.uvs[m.faceUvs[f][k]], ref.uvs[ref.faceUvs[f][k]]));
            }
        EXPECT_LT(worstP, 1e-7);  // float32 in the file
        EXPECT_LT(worstUv, 1e-7);
    }
}

TEST(GltfMesh, knitOnGltfCylinderMatchesBuiltInCylinder) {
    knit::BaseMesh ref;
    const GltfBuilder g = cylinderGltf(ref);
    knit::SceneOptions so;
    so.placement.repeats = {8, 4};
    so.buildPlies = false;
    const knit::Scene a = knit::buildScene(knit::generateStockinette(), ref, so);
    const knit::Scene b = knit::buildScene(knit::generateStockinette(), knit::parseGltfMesh(g.glb(), "c.glb", ""), so);
    EXPECT_EQ(a.bindStats().closedLoops, b.bindStats().closedLoops);  // courses close across the welded seam
    EXPECT_GT(b.bindStats().closedLoops, 0u);
    ASSERT_EQ(a.yarns().curves.pointCount(), b.yarns().curves.pointCount());
    double worst = 0;
    for (size_t i = 0; i < a.yarns().curves.pointCount(); ++i)
        worst = std::max(worst, glm::distance(a.yarns().curves.points[i], b.yarns().curves.points[i]));
    EXPECT_LT(worst, 1e-6);
}

TEST(GltfMesh, nodeTransformsAreComposedDownTheTree) {
    // Root: translate (1, 2, 3), rotate 90 degrees about z, scale 2; child: a matrix moving +5 in x.
    const std::string bytes = quadFile([](GltfBuilder& g) {
        const double s = std::sqrt(0.5);
        g.doc["nodes"] = json::array(
            {{{"translation", {1, 2, 3}}, {"rotation", {0, 0, s, s}}, {"scale", {2, 2, 2}}, {"children", {1}}},
             {{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}}}});
    });
    const knit::BaseMesh m = knit::parseGltfMesh(bytes, "t.gltf", "");
    ASSERT_EQ(m.positions.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 local(kQuadPos[3 * i] + 5.0, kQuadPos[3 * i + 1], kQuadPos[3 * i + 2]);
        const glm::dvec3 expected = glm::dvec3(1, 2, 3) + 2.0 * glm::dvec3(-local.y, local.x, local.z);
        EXPECT_LT(glm::distance(m.positions[size_t(i)], expected), 1e-12) << i;
    }
}

TEST(GltfMesh, stripsFansAndUnindexedTrianglesGiveTheSameQuad) {
    const knit::BaseMesh tri = knit::parseGltfMesh(quadFile([](GltfBuilder&) {}), "q.gltf", "");
    ASSERT_EQ(tri.faceCount(), 2u);
    auto area = [](const knit::BaseMesh& m) {
        double a = 0;
        for (const glm::uvec3& f : m.faces)
            a +=
                0.5 * glm::length(glm::cross(m.positions[f.y] - m.positions[f.x], m.positions[f.z] - m.positions[f.x]));
        return a;
    };
    struct Case {
        std::vector<uint32_t> idx;
        int mode;
    };
    for (const Case& c : {Case{{0, 1, 3, 2}, 5}, Case{{0, 1, 2, 3}, 6}, Case{{}, 4}}) {
        const std::string bytes = quadFile([&](GltfBuilder& g) {
            g.doc["meshes"] = json::array();
            if (c.idx.empty()) {  // unindexed: six corners
                const std::vector<float> p{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
                const std::vector<float> t{0, 1, 1, 1, 1, 0, 0, 1, 1, 0, 0, 0};
                g.mesh(p, t, {}, c.mode);
            } else {
                g.mesh(kQuadPos, kQuadUv, c.idx, c.mode);
            }
        });
        const knit::BaseMesh m = knit::parseGltfMesh(bytes, "q.gltf", "");
        EXPECT_EQ(m.faceCount(), 2u) << "mode " << c.mode;
        EXPECT_EQ(m.positions.size(), 4u) << "mode " << c.mode;
        EXPECT_NEAR(area(m), 1.0, 1e-12) << "mode " << c.mode;
        for (const glm::dvec2& uv : m.uvs) EXPECT_TRUE((uv.x == 0 || uv.x == 1) && (uv.y == 0 || uv.y == 1));
    }
}

TEST(GltfMesh, quantizedTexcoordsAreNormalized) {
    const std::string bytes = quadFile([](GltfBuilder& g) {
        const std::vector<uint16_t> uv{0, 65535, 65535, 65535, 65535, 0, 0, 0};
        g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = g.accessor(uv, 5123, "VEC2", 4, true);
    });
    const knit::BaseMesh m = knit::parseGltfMesh(bytes, "q.gltf", "");
    for (size_t f = 0; f < m.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = m.positions[m.faces[f][k]];
            EXPECT_EQ(m.uvs[m.faceUvs[f][k]], glm::dvec2(p.x, p.y));  // uv = xy exactly
        }
}

TEST(GltfMesh, externalBufferIsReadNextToTheFile) {
    knit_test::TempDir dir;
    GltfBuilder g;
    g.mesh(kQuadPos, kQuadUv, {0, 1, 2, 0, 2, 3});
    dir.write("quad.bin", g.bin);
    const std::string path = dir.write("quad.gltf", g.gltfExternal("quad.bin"));
    EXPECT_EQ(knit::loadMesh(path).faceCount(), 2u);  // no scenes: every mesh once
    const std::string glb = dir.write("quad.glb", g.glb());
    EXPECT_EQ(knit::loadMesh(glb).faceCount(), 2u);
    // From memory without a folder, external files are refused.
    EXPECT_NE(errorOf([&] { knit::parseGltfMesh(g.gltfExternal("quad.bin"), "mem.gltf", ""); }).find("not allowed"),
              std::string::npos);
    // A .bin shorter than its byteLength is refused; a missing one names the file.
    dir.write("quad.bin", g.bin.substr(0, 10));
    EXPECT_NE(errorOf([&] { knit::loadMesh(path); }).find("less than the buffer's byteLength"), std::string::npos);
    std::filesystem::remove(dir.file("quad.bin"));
    EXPECT_NE(errorOf([&] { knit::loadMesh(path); }).find(path), std::string::npos);
}

// glTF: a transform with negative determinant reverses the winding, so a mirrored instance is not
// turned inside out (its geometric normals point the way the mirror image of the original's do).
TEST(GltfMesh, mirroredNodesKeepTheirTrianglesOutwardFacing) {
    for (const double sx : {1.0, -1.0}) {
        const std::string bytes = quadFile([&](GltfBuilder& g) { g.doc["nodes"][0]["scale"] = {sx, 1, 1}; });
        const knit::BaseMesh m = knit::parseGltfMesh(bytes, "m.gltf", "");
        ASSERT_EQ(m.faceCount(), 2u);
        for (const glm::uvec3& f : m.faces) {
            const glm::dvec3 n = glm::cross(m.positions[f.y] - m.positions[f.x], m.positions[f.z] - m.positions[f.x]);
            EXPECT_GT(n.z, 0) << "scale x " << sx;  // the quad faces +z before and after mirroring x
        }
    }
}

// A 20000-deep chain of nodes is walked without recursion; the translations add up.
TEST(GltfMesh, deepNodeChainsDoNotOverflowTheStack) {
    const int depth = 20000;
    const std::string bytes = quadFile([&](GltfBuilder& g) {
        json nodes = json::array();
        for (int k = 0; k < depth; ++k) {
            json n = {{"translation", {0.001, 0, 0}}};
            if (k + 1 < depth) n["children"] = {k + 1};
            else n["mesh"] = 0;
            nodes.push_back(n);
        }
        g.doc["nodes"] = nodes;
    });
    const knit::BaseMesh m = knit::parseGltfMesh(bytes, "deep.gltf", "");
    double minX = 1e9;
    for (const glm::dvec3& p : m.positions) minX = std::min(minX, p.x);
    EXPECT_NEAR(minX, 0.001 * depth, 1e-9);
}

// Instancing multiplies a small file; the total is capped by MeshLoadOptions::maxElements.
// The quad's one mesh (its accessors) instanced by 100 nodes side by side.
std::string hundredQuadInstances() {
    return quadFile([](GltfBuilder& g) {
        g.doc["nodes"] = json::array();
        for (int k = 0; k < 100; ++k) g.doc["nodes"].push_back({{"mesh", 0}, {"translation", {2.0 * k, 0, 0}}});
        json roots = json::array();
        for (int k = 0; k < 100; ++k) roots.push_back(k);
        g.doc["scenes"][0]["nodes"] = roots;
    });
}

TEST(GltfMesh, instancingBeyondTheElementBudgetIsRefused) {
    const std::string bytes = hundredQuadInstances();
    EXPECT_EQ(knit::parseGltfMesh(bytes, "many.gltf", "").faceCount(), 200u);
    knit::MeshLoadOptions o;
    o.maxElements = 150;
    EXPECT_NE(errorOf([&] { knit::parseGltfMesh(bytes, "many.gltf", "", o); }).find("more than 150 vertices"),
              std::string::npos);
}

// One accessor reused by many instances: the expanded size (100 x 4 vertices x 96 B + 100 x 6
// indices x 24 B = 52800 B) is estimated before any is expanded and checked against the budget.
TEST(GltfMesh, accessorsReusedByManyInstancesAreRefusedOverTheMemoryBudget) {
    const std::string bytes = hundredQuadInstances();
    knit::MeshLoadOptions o;
    o.budget = knit::MemoryBudget(50000);
    const std::string m = errorOf([&] { knit::parseGltfMesh(bytes, "many.gltf", "", o); });
    EXPECT_NE(m.find("for 400 vertices and 600 indices of 100 primitive instances in 'many.gltf'"), std::string::npos)
        << m;
    EXPECT_NE(m.find("raise the memory budget"), std::string::npos) << m;
    o.budget = knit::MemoryBudget(60000);
    EXPECT_EQ(knit::parseGltfMesh(bytes, "many.gltf", "", o).faceCount(), 200u);
}

// Bad files: knit::Error naming what is wrong, never a crash.
TEST(GltfMesh, badFilesAreRefusedWithAReason) {
    struct Bad {
        const char* name;
        std::function<void(GltfBuilder&)> edit;
        const char* expected;
    };
    const std::vector<Bad> cases = {
        {"noTexcoord", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0"); },
         "has no TEXCOORD_0"},
        {"noPosition", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); },
         "has no POSITION"},
        {"indexOutOfRange",
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["indices"] =
                 g.accessor(std::vector<uint32_t>{0, 1, 7}, 5125, "SCALAR", 3);
         },
         "index 2 is 7"},
        {"normalizedIndices",  // each would read as a fraction of 255: 0 or 1
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["indices"] =
                 g.accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, 5121, "SCALAR", 6, true);
         },
         "indices must be unsigned byte, short or int scalars, not normalized"},
        {"accessorPastItsView", [](GltfBuilder& g) { g.doc["accessors"][1]["count"] = 400; }, ""},
        {"draco",
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["extensions"] = {
                 {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", json::object()}}}};
         },
         "Draco"},
        {"notWholeTriangles",
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["indices"] =
                 g.accessor(std::vector<uint32_t>{0, 1, 2, 3}, 5125, "SCALAR", 4);
         },
         "whole triangles"},
        {"nodeCycle",
         [](GltfBuilder& g) {
             g.doc["nodes"] = json::array({{{"mesh", 0}, {"children", {0}}}});
         },
         "reached twice"},
        {"onlyLines", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 1; },
         "no triangle primitives"},
        {"texcoordCountDiffers",
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
                 g.accessor(std::vector<float>{0, 0, 1, 0}, 5126, "VEC2", 2);
         },
         "TEXCOORD_0 has 2 elements"},
        {"nanPosition",
         [](GltfBuilder& g) {
             g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
                 g.accessor(std::vector<float>{0, 0, 0, 1, 0, 0, 1, std::nanf(""), 0, 0, 1, 0}, 5126, "VEC3", 4);
         },
         "non-finite position"},
        {"nodeTranslationBeyondFloat32",
         [](GltfBuilder& g) {
             g.doc["nodes"] = json::array({{{"mesh", 0}, {"name", "arm"}, {"translation", {1e39, 0, 0}}}});
         },
         "nodes[0] ('arm').translation holds 1e+39, beyond the float32 range (3.4e38)"},
        {"nodeScalesWhoseProductPassesFloat32",
         [](GltfBuilder& g) {
             g.doc["nodes"] = json::array({{{"scale", {1e20, 1e20, 1e20}}, {"children", {1}}},
                                           {{"mesh", 0}, {"name", "hand"}, {"scale", {1e20, 1e20, 1e20}}}});
         },
         "nodes[1] ('hand'): its transform times its parents' reaches 1e+40"},
    };
    for (const Bad& c : cases)
        for (const bool binary : {false, true}) {
            const std::string bytes = quadFile(c.edit, binary);
            const std::string e = errorOf([&] { knit::parseGltfMesh(bytes, "bad.gltf", ""); });
            EXPECT_NE(e.find("bad.gltf"), std::string::npos) << c.name << ": " << e;
            EXPECT_EQ(e.find("no knit::Error"), std::string::npos) << c.name;
            EXPECT_NE(e.find(c.expected), std::string::npos) << c.name << ": " << e;
        }
    // Not glTF at all, truncated GLB, a file with another extension's content.
    const std::string glb = quadFile([](GltfBuilder&) {}, true);
    for (const std::string& bytes :
         {std::string("{not json"), glb.substr(0, glb.size() / 2), std::string("glTF"), std::string()}) {
        const std::string e = errorOf([&] { knit::parseGltfMesh(bytes, "bad.glb", ""); });
        EXPECT_NE(e.find("bad.glb"), std::string::npos) << e;
    }
}

}  // namespace
