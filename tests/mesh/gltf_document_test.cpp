// gltf::Document, the project's one glTF reader (libknit/src/internal/io/gltf_document.hpp): what the export
// tests and the speed-vs-error tool use beyond base meshes (tests/mesh/gltf_mesh_test.cpp covers
// the checks a base mesh meets). Files are assembled with gltf_builder.hpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/gltf_document.hpp"
#include "knit/error.hpp"
#include "mesh/gltf_builder.hpp"
#include "mesh/mesh_test_util.hpp"

namespace {

using knit_test::errorOf;
using knit_test::GltfBuilder;
using nlohmann::json;
namespace gltf = knit::gltf;

// One mesh whose only primitive is a line strip over `n` float VEC3 points (no indices).
int lineStrip(GltfBuilder& g, size_t n) {
    std::vector<float> p;
    for (size_t i = 0; i < n; ++i) p.insert(p.end(), {float(i), 0.0f, 0.0f});
    const int pos = g.accessor(p, gltf::kFloat, "VEC3", n);
    g.doc["meshes"].push_back(
        {{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", gltf::kLineStrip}}})}});
    return int(g.doc["meshes"].size()) - 1;
}

TEST(GltfDocument, interleavedNormalizedComponentsAreDecodedWithTheViewsStride) {
    // Two elements of (u16 x2, i8 x2) interleaved in 8-byte strides: view stride, not element size.
    GltfBuilder g;
    const std::vector<uint8_t> bytes{0xFF, 0xFF, 0x00, 0x00, 0x81, 0x7F, 0, 0,   // 65535, 0 | -127, 127
                                     0x00, 0x80, 0x01, 0x00, 0x80, 0x00, 0, 0};  // 32768, 1 | -128, 0
    g.accessor(bytes, gltf::kUnsignedShort, "VEC2", 2, true);
    g.doc["bufferViews"][0]["byteStride"] = 8;
    g.doc["accessors"].push_back({{"bufferView", 0},
                                  {"byteOffset", 4},
                                  {"componentType", gltf::kByte},
                                  {"type", "VEC2"},
                                  {"count", 2},
                                  {"normalized", true}});
    const gltf::Document d(g.glb(), "interleaved.glb", "");
    EXPECT_EQ(d.accessor(0, "test").values(), (std::vector<double>{1.0, 0.0, 32768 / 65535.0, 1 / 65535.0}));
    EXPECT_EQ(d.accessor(1, "test").values(), (std::vector<double>{-1.0, 1.0, -1.0, 0.0}));  // -128 clamps to -1
}

TEST(GltfDocument, bufferViewBytesStayInsideTheirBuffer) {
    GltfBuilder g;
    g.accessor(std::vector<uint32_t>{7, 8, 9}, gltf::kUnsignedInt, "SCALAR", 3);
    g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 4}, {"byteLength", 8}});
    g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 8}, {"byteLength", 8}});
    const gltf::Document d(g.gltf(), "views.gltf", "");
    const gltf::Bytes b = d.bufferView(1, "Draco data");
    ASSERT_EQ(b.size, 8u);
    EXPECT_EQ(b.data[0], 8);
    EXPECT_EQ(b.data[4], 9);
    EXPECT_EQ(errorOf([&] { d.bufferView(2, "Draco data"); }),
              "views.gltf: Draco data: bufferViews[2] lies outside its buffer");
}

TEST(GltfDocument, meshInstancesFollowTheNodeTreeInFileOrderWithWorldTransforms) {
    GltfBuilder g;
    const int a = lineStrip(g, 2), b = lineStrip(g, 3);
    g.doc["nodes"] = json::array({{{"children", {2, 1}}, {"translation", {1, 0, 0}}},
                                  {{"mesh", a}, {"translation", {0, 2, 0}}},
                                  {{"mesh", b}, {"scale", {3, 3, 3}}}});
    g.doc["scenes"] = json::array({{{"nodes", {0}}}});
    const gltf::Document d(g.gltf(), "tree.gltf", "");
    const std::vector<gltf::MeshInstance> inst = d.meshInstances();
    ASSERT_EQ(inst.size(), 2u);
    EXPECT_EQ(inst[0].mesh, size_t(b));  // children in the order listed
    EXPECT_EQ(inst[0].node, 2u);
    EXPECT_EQ(inst[0].world * glm::dvec4(1, 0, 0, 1), glm::dvec4(4, 0, 0, 1));
    EXPECT_EQ(inst[1].node, 1u);
    EXPECT_EQ(inst[1].world * glm::dvec4(0, 0, 0, 1), glm::dvec4(1, 2, 0, 1));

    g.doc.erase("scenes");  // no scenes: every mesh once, untransformed, without a node
    const std::vector<gltf::MeshInstance> all = gltf::Document(g.gltf(), "flat.gltf", "").meshInstances();
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[1].mesh, size_t(b));
    EXPECT_EQ(all[1].node, gltf::MeshInstance::kNoNode);
    EXPECT_EQ(all[1].world, glm::dmat4(1.0));
}

TEST(GltfDocument, primitivesGiveModeAttributesIndicesAndExtensions) {
    GltfBuilder g;
    lineStrip(g, 4);
    g.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}},
                                                {"indices", 0},
                                                {"mode", 4},
                                                {"extensions", {{"KHR_draco_mesh_compression", json::object()}}}});
    g.doc["meshes"][0]["name"] = "curves";
    g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression", "KHR_materials_sheen"};
    g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const gltf::Document d(g.gltf(), "prims.gltf", "");
    const std::vector<gltf::Primitive> p = d.primitives(0);
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0].mode, size_t(gltf::kLineStrip));
    EXPECT_EQ(p[0].what, "mesh 0 ('curves') primitive 0");
    EXPECT_FALSE(d.indices(p[0]));
    EXPECT_EQ(d.attribute(p[0], "POSITION"), std::optional<size_t>(0));
    EXPECT_FALSE(d.attribute(p[0], "NORMAL"));
    EXPECT_TRUE(d.extensions(p[0]).empty());
    EXPECT_EQ(d.indices(p[1]), std::optional<size_t>(0));
    EXPECT_TRUE(d.extensions(p[1]).contains("KHR_draco_mesh_compression"));
    EXPECT_EQ(d.extensionsUsed(), (std::vector<std::string>{"KHR_draco_mesh_compression", "KHR_materials_sheen"}));
    EXPECT_EQ(d.extensionsRequired(), std::vector<std::string>{"KHR_draco_mesh_compression"});
}

TEST(GltfDocument, glbLayoutReportsTheChunkHeaders) {
    GltfBuilder g;
    lineStrip(g, 3);  // 36 bytes of BIN
    const std::string bytes = g.glb();
    const gltf::Document d(bytes, "layout.glb", "");
    const gltf::GlbLayout& l = d.glbLayout();
    EXPECT_TRUE(l.glb);
    EXPECT_EQ(l.length, bytes.size());
    EXPECT_EQ(l.jsonLength % 4, 0u);
    EXPECT_TRUE(l.secondChunk);
    EXPECT_EQ(l.secondType, 0x004E4942u);
    EXPECT_EQ(l.secondLength, 36u);
    EXPECT_FALSE(gltf::Document(g.gltf(), "layout.gltf", "").glbLayout().glb);
}

TEST(GltfDocument, sparseAndViewlessAccessorsAreRefusedNamingTheUse) {
    GltfBuilder g;
    lineStrip(g, 2);
    g.doc["accessors"].push_back({{"componentType", gltf::kFloat}, {"type", "VEC3"}, {"count", 2}});  // Draco style
    g.doc["accessors"].push_back({{"bufferView", 0},
                                  {"componentType", gltf::kFloat},
                                  {"type", "VEC3"},
                                  {"count", 2},
                                  {"sparse", {{"count", 1}}}});
    const gltf::Document d(g.gltf(), "refused.gltf", "");
    EXPECT_EQ(errorOf([&] { d.accessor(1, "NORMAL"); }),
              "refused.gltf: NORMAL: accessors[1] has no data (no bufferView)");
    EXPECT_EQ(errorOf([&] { d.accessor(2, "NORMAL"); }), "refused.gltf: NORMAL: sparse accessors are not supported");
}

}  // namespace
