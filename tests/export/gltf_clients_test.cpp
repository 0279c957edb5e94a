// glTF conventions real clients rely on (issue 14): TANGENT along u of the file's own TEXCOORD_0
// with the bitangent sign in w, linear COLOR_0, UNSIGNED_SHORT indices where a chunk fits,
// quantized TEXCOORD_0 with its scale, EXT_meshopt_compression views that decode to the plain
// data, and the curves' _RADIUS attribute named in the asset extras.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "export/export_helpers.hpp"
#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"

#ifdef KNIT_WITH_MESHOPT
#include <meshoptimizer.h>
#endif

namespace knit {
namespace {

// One triangle primitive read back: world positions, normals, tangents, uvs and indices.
struct Triangles {
    std::vector<glm::dvec3> p, n;
    std::vector<glm::dvec4> t;
    std::vector<glm::dvec2> uv;
    std::vector<size_t> idx;
};

Triangles readFirstPrimitive(const gltf::Document& d) {
    Triangles r;
    const gltf::MeshInstance inst = d.meshInstances().at(0);
    const gltf::Primitive prim = d.primitives(inst.mesh).at(0);
    r.p = test::worldPositions(d, prim, inst.world);
    const auto n = test::readAttribute(d, prim, "NORMAL"), t = test::readAttribute(d, prim, "TANGENT"),
               uv = test::readAttribute(d, prim, "TEXCOORD_0");
    for (size_t i = 0; i < r.p.size(); ++i) {
        r.n.emplace_back(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
        r.t.emplace_back(t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]);
        r.uv.emplace_back(uv[2 * i], uv[2 * i + 1]);
    }
    for (double i : test::readAccessor(d, *d.indices(prim))) r.idx.push_back(size_t(i));
    return r;
}

TEST(GltfClients, tangentIsDPduOfTheFilesOwnTexcoordsWithBitangentSignInW) {
    const std::string dir = test::scratchDir("gltf_clients_tangent");
    const Polylines c = test::mixedCurves();
    test::exportWith(c, 0.0015, test::tubeOptions(dir + "/t.glb", 16));
    const Triangles r = readFirstPrimitive(test::loadGltf(dir + "/t.glb"));
    ASSERT_GT(r.idx.size(), 0u);
    for (size_t f = 0; f + 2 < r.idx.size(); f += 3) {
        const size_t a = r.idx[f], b = r.idx[f + 1], e = r.idx[f + 2];
        const glm::dvec3 e1 = r.p[b] - r.p[a], e2 = r.p[e] - r.p[a];
        const glm::dvec2 d1 = r.uv[b] - r.uv[a], d2 = r.uv[e] - r.uv[a];
        const double det = d1.x * d2.y - d2.x * d1.y;
        ASSERT_NE(det, 0.0) << "triangle " << f / 3;
        const glm::dvec3 dPdu = (e1 * d2.y - e2 * d1.y) / det, dPdv = (e2 * d1.x - e1 * d2.x) / det;
        for (size_t v : {a, b, e}) {
            const glm::dvec3 t(r.t[v]);
            // Along u, not v (0): the test curves are coarse, so ring frames turn between rings and
            // a triangle's dP/du mixes two rings' chords; sweep_test pins it tightly.
            ASSERT_GT(glm::dot(t, glm::normalize(dPdu)), 0.7) << "vertex " << v;
            ASSERT_GT(r.t[v].w * glm::dot(glm::cross(r.n[v], t), dPdv), 0.0) << "vertex " << v;
        }
    }
}

TEST(GltfClients, yarnColourIsThePaletteColourConvertedToLinear) {
    const std::string dir = test::scratchDir("gltf_clients_colour");
    const Polylines c = test::mixedCurves();
    ExportOptions o = test::tubeOptions(dir + "/c.glb", 4);
    o.yarnColors = true;
    const std::vector<uint32_t> yarns(c.curveCount(), 0);
    test::exportWith(c, 0.001, o, &yarns);
    const gltf::Document d = test::loadGltf(o.path);
    const gltf::Primitive prim = d.primitives(d.meshInstances().at(0).mesh).at(0);
    const std::vector<double> col = test::readAttribute(d, prim, "COLOR_0");
    // Yarn 0's palette colour in sRGB: hue 0.13 x 6 = 0.78 of sector 0, s = 0.55, v = 0.9.
    const double srgb[3] = {0.9, 0.9 * (1 - 0.55 * (1 - 0.78)), 0.9 * (1 - 0.55)};
    for (int k = 0; k < 3; ++k) {
        const double linear = std::pow((srgb[k] + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(col[size_t(k)], linear, 0.5 / 255 + 1e-9) << "channel " << k;
    }
    EXPECT_EQ(col[3], 1.0);
}

TEST(GltfClients, chunksUpTo65535VerticesGetUnsignedShortIndices) {
    const std::string dir = test::scratchDir("gltf_clients_indices");
    const Polylines c = test::mixedCurves();
    test::exportWith(c, 0.001, test::tubeOptions(dir + "/small.glb", 8));
    const gltf::Document small = test::loadGltf(dir + "/small.glb");
    EXPECT_EQ(
        small.root()["accessors"][small.root()["meshes"][0]["primitives"][0]["indices"].get<size_t>()]["componentType"],
        gltf::kUnsignedShort);
    test::expectGltfValid(dir + "/small.glb");
    // 1024 sides: one chunk of more than 65535 vertices keeps UNSIGNED_INT.
    const ExportStats s = test::exportWith(c, 0.001, test::tubeOptions(dir + "/large.glb", 1024));
    ASSERT_GT(s.maxChunkVertices, 65535u);
    const gltf::Document large = test::loadGltf(dir + "/large.glb");
    EXPECT_EQ(
        large.root()["accessors"][large.root()["meshes"][0]["primitives"][0]["indices"].get<size_t>()]["componentType"],
        gltf::kUnsignedInt);
}

TEST(GltfClients, quantizedTexcoordsTimesTheirScaleGiveThePlainTexcoords) {
    const std::string dir = test::scratchDir("gltf_clients_uv");
    const Polylines c = test::mixedCurves();
    test::exportWith(c, 0.001, test::tubeOptions(dir + "/plain.glb", 8));
    ExportOptions o = test::tubeOptions(dir + "/q.glb", 8);
    o.quantize = true;
    test::exportWith(c, 0.001, o);
    test::expectGltfValid(o.path);
    const gltf::Document plain = test::loadGltf(dir + "/plain.glb"), q = test::loadGltf(o.path);
    const gltf::Primitive pp = plain.primitives(0).at(0), qp = q.primitives(0).at(0);
    const nlohmann::json& scale = q.root()["meshes"][0]["primitives"][0]["extras"]["texcoordScale"];
    ASSERT_EQ(scale.size(), 2u);
    const std::vector<double> a = test::readAttribute(plain, pp, "TEXCOORD_0"),
                              b = test::readAttribute(q, qp, "TEXCOORD_0");
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        const double s = scale[i % 2].get<double>();
        ASSERT_NEAR(b[i] * s, a[i], 0.5 / 65535 * s + 1e-6 * s) << i;
    }
}

TEST(GltfClients, curveFileNamesTheRadiusAttributeInAssetExtras) {
    const std::string dir = test::scratchDir("gltf_clients_radius");
    const Polylines c = test::mixedCurves();
    ExportOptions o;
    o.path = dir + "/curves.glb";
    o.what = ExportWhat::Yarns;
    test::exportWith(c, 0.002, o);
    test::expectGltfValid(o.path);
    const gltf::Document d = test::loadGltf(o.path);
    const nlohmann::json& asset = d.root()["asset"];
    ASSERT_TRUE(asset.contains("extras"));
    EXPECT_NE(asset["extras"]["attributes"]["_RADIUS"].get<std::string>().find("radius"), std::string::npos);
    const gltf::Primitive prim = d.primitives(0).at(0);
    for (double r : test::readAttribute(d, prim, "_RADIUS")) ASSERT_FLOAT_EQ(float(r), 0.002f);
}

// meshopt compression needs a glTF output and tubes, and is an alternative to Draco (messages name
// the setting in words).
TEST(GltfClients, meshoptNeedsGltfTubesAndIsNoDracoCompanion) {
    const std::string dir = test::scratchDir("gltf_clients_meshopt_errors");
    const Polylines c = test::mixedCurves();
    auto errorOf = [&](ExportOptions o) {
        try {
            test::exportWith(c, 0.001, o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    ExportOptions obj = test::tubeOptions(dir + "/t.obj", 8);
    obj.meshopt = true;
    EXPECT_EQ(errorOf(obj),
              "cannot export '" + obj.path +
                  "': meshopt compression needs a .glb or .gltf output (EXT_meshopt_compression is a glTF extension)");
    ExportOptions curves;
    curves.path = dir + "/c.glb";
    curves.meshopt = true;
    EXPECT_EQ(errorOf(curves),
              "cannot export '" + curves.path +
                  "': meshopt compression applies to tube meshes only; what to export is plies, not tubes");
    ExportOptions both = test::tubeOptions(dir + "/b.glb", 8);
    both.meshopt = both.draco = true;
    EXPECT_EQ(errorOf(both), "cannot export '" + both.path +
                                 "': Draco compression and meshopt compression are alternatives; choose one");
}

#ifdef KNIT_WITH_MESHOPT
// Each EXT_meshopt_compression view decodes (meshoptimizer's decoders) to exactly the bytes of
// the same view of the uncompressed export; the views live in a fallback buffer without data.
TEST(GltfClients, meshoptViewsDecodeToThePlainExportsBytes) {
    const std::string dir = test::scratchDir("gltf_clients_meshopt");
    const Polylines c = test::mixedCurves();
    test::exportWith(c, 0.001, test::tubeOptions(dir + "/plain.glb", 8));
    ExportOptions o = test::tubeOptions(dir + "/m.glb", 8);
    o.meshopt = true;
    const ExportStats s = test::exportWith(c, 0.001, o);
    test::expectGltfValid(o.path);
    const gltf::Document plain = test::loadGltf(dir + "/plain.glb"), m = test::loadGltf(o.path);
    const nlohmann::json& root = m.root();
    const std::vector<std::string> required = m.extensionsRequired();
    EXPECT_NE(std::find(required.begin(), required.end(), "EXT_meshopt_compression"), required.end());
    const nlohmann::json& fallback = root["buffers"].back();
    EXPECT_FALSE(fallback.contains("uri"));
    EXPECT_TRUE(fallback["extensions"]["EXT_meshopt_compression"]["fallback"].get<bool>());
    const size_t fallbackIndex = root["buffers"].size() - 1;
    ASSERT_EQ(root["bufferViews"].size(), plain.root()["bufferViews"].size());
    const std::vector<unsigned char>& bin = m.buffer(0, "test");
    for (size_t v = 0; v < root["bufferViews"].size(); ++v) {
        const nlohmann::json& view = root["bufferViews"][v];
        EXPECT_EQ(view["buffer"].get<size_t>(), fallbackIndex);
        const nlohmann::json& ext = view["extensions"]["EXT_meshopt_compression"];
        const size_t count = ext["count"], stride = ext["byteStride"], at = ext["byteOffset"], len = ext["byteLength"];
        std::vector<unsigned char> decoded(count * stride);
        const int rc = ext["mode"] == "TRIANGLES"
                           ? meshopt_decodeIndexBuffer(decoded.data(), count, stride, bin.data() + at, len)
                           : meshopt_decodeVertexBuffer(decoded.data(), count, stride, bin.data() + at, len);
        ASSERT_EQ(rc, 0) << "view " << v;
        const gltf::Bytes want = plain.bufferView(v, "test");
        ASSERT_EQ(decoded.size(), want.size) << "view " << v;
        if (ext["mode"] == "TRIANGLES") {
            // The index codec may rotate a triangle's corners (keeping its winding).
            ASSERT_EQ(stride, 2u);
            std::vector<uint16_t> got(count), exp(count);
            std::memcpy(got.data(), decoded.data(), decoded.size());
            std::memcpy(exp.data(), want.data, want.size);
            for (size_t f = 0; f < count; f += 3) {
                bool same = false;
                for (size_t r = 0; r < 3 && !same; ++r)
                    same = got[f] == exp[f + r] && got[f + 1] == exp[f + (r + 1) % 3] &&
                           got[f + 2] == exp[f + (r + 2) % 3];
                ASSERT_TRUE(same) << "triangle " << f / 3;
            }
        } else {
            EXPECT_EQ(std::memcmp(decoded.data(), want.data, want.size), 0) << "view " << v;
        }
    }
    EXPECT_LT(s.bytes, test::readBytes(dir + "/plain.glb").size());
}
#endif

}  // namespace
}  // namespace knit
