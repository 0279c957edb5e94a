// Messages with the real cause (docs/hard-cases.md, "Error"): inputs refused for a reason the
// message names, not for a symptom further down.
#include <gtest/gtest.h>

#include <string>

#include "knit/base_mesh.hpp"
#include "scene_refusals.hpp"
#include "test_util.hpp"

namespace {

using knit::test::errorOf;

// A triangle whose buffer views are meshopt-compressed: the fallback buffer has no data.
TEST(Messages, meshoptCompressedGltfIsNamedNotAMissingBuffer) {
    const std::string gltf = R"({"asset": {"version": "2.0"},
        "extensionsUsed": ["EXT_meshopt_compression"], "extensionsRequired": ["EXT_meshopt_compression"],
        "buffers": [{"byteLength": 60, "extensions": {"EXT_meshopt_compression": {"fallback": true}}},
                    {"byteLength": 20, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAAAAAAAAAAA="}],
        "bufferViews": [{"buffer": 0, "byteLength": 60, "extensions": {"EXT_meshopt_compression":
            {"buffer": 1, "byteLength": 20, "byteStride": 12, "count": 3, "mode": "ATTRIBUTES"}}}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC2"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
    const std::string m = errorOf([&] { knit::parseGltfMesh(gltf, "meshopt.gltf", ""); });
    EXPECT_NE(m.find("EXT_meshopt_compression is not supported"), std::string::npos) << m;
    EXPECT_NE(m.find("meshopt.gltf"), std::string::npos) << m;
}

// OFF allows a colour after each face's indices (integer or float RGB or RGBA); it was refused
// as "face 1 has 1 corners" when float.
TEST(Messages, offWithFaceColoursIsReadLikeWithout) {
    knit::test::TempDir tmp;
    const std::string vertices = "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n";
    tmp.write("plain.off", vertices + "3 0 1 2\n3 0 2 3\n");
    tmp.write("colours.off", vertices + "3 0 1 2 1.0 0.0 0.0\n3 0 2 3 128 128 128 255\n");
    const knit::BaseMesh plain = knit::loadMesh((tmp.path() / "plain.off").string());
    const knit::BaseMesh colours = knit::loadMesh((tmp.path() / "colours.off").string());
    EXPECT_EQ(colours.faces, plain.faces);
    EXPECT_EQ(colours.positions, plain.positions);
    EXPECT_EQ(colours.uvs, plain.uvs);
}

}  // namespace
