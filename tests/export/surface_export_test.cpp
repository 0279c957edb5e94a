// The surface level's GLB: the base mesh with the baked textures as a glTF PBR material.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include <stb/stb_image.h>

#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/plies.hpp"
#include "knit/surface_export.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

namespace fs = std::filesystem;

// A small image pair with distinct texels (so a decoded image can be compared pixel by pixel).
SurfaceImages testImages(int w, int h) {
    SurfaceImages im;
    im.width = w, im.height = h;
    for (int i = 0; i < w * h; ++i) {
        const uint8_t v = uint8_t(7 * i);
        im.baseColorRgba.insert(im.baseColorRgba.end(), {v, uint8_t(255 - v), 90, uint8_t(i % 2 ? 255 : 40)});
        im.normalRgb.insert(im.normalRgb.end(), {128, uint8_t(100 + i % 50), 230});
    }
    return im;
}

std::string tempGlb(const char* name) {
    return (fs::temp_directory_path() / (std::string("knit_surface_") + std::to_string(::getpid()) + name)).string();
}

// Options writing to a temporary GLB of that name.
SurfaceExportOptions toTemp(const char* name, glm::dvec2 repeats = {1, 1}) {
    SurfaceExportOptions o;
    o.path = tempGlb(name);
    o.repeats = repeats;
    return o;
}

// The PNG bytes of image `i` of a document, decoded: width, height and pixels.
std::vector<uint8_t> decodeImage(const gltf::Document& d, size_t i, int& w, int& h, int channels) {
    const size_t view = d.root()["images"][i]["bufferView"].get<size_t>();
    const gltf::Bytes b = d.bufferView(view, "image");
    int n = 0;
    unsigned char* px = stbi_load_from_memory(b.data, int(b.size), &w, &h, &n, channels);
    std::vector<uint8_t> out(px, px + size_t(w) * h * channels);
    stbi_image_free(px);
    return out;
}

TEST(SurfaceExport, glbPassesTheValidatorWithATexturedRepeatingMaterial) {
    const SurfaceExportOptions o = toTemp("valid.glb", {3, 2});
    const std::string& path = o.path;
    const SurfaceImages im = testImages(8, 6);
    const SurfaceExportStats s = exportSurface(makePlane(), im, o);
    EXPECT_EQ(s.bytes, fs::file_size(path));
    test::expectGltfValid(path);
    const gltf::Document d = test::loadGltf(path);
    const nlohmann::json& m = d.root()["materials"][0];
    EXPECT_EQ(m["alphaMode"], "MASK");
    ASSERT_TRUE(m["pbrMetallicRoughness"].contains("baseColorTexture"));
    ASSERT_TRUE(m.contains("normalTexture"));
    const nlohmann::json& sampler = d.root()["samplers"][0];
    EXPECT_EQ(sampler["wrapS"], 10497);  // REPEAT
    EXPECT_EQ(sampler["wrapT"], 10497);
    // The embedded PNGs decode to the images given, texel for texel.
    const size_t colour =
        d.root()["textures"][m["pbrMetallicRoughness"]["baseColorTexture"]["index"].get<size_t>()]["source"];
    int w = 0, h = 0;
    EXPECT_EQ(decodeImage(d, colour, w, h, 4), im.baseColorRgba);
    EXPECT_EQ(w, 8);
    EXPECT_EQ(h, 6);
    const size_t normal = d.root()["textures"][m["normalTexture"]["index"].get<size_t>()]["source"];
    EXPECT_EQ(decodeImage(d, normal, w, h, 3), im.normalRgb);
    fs::remove(path);
}

// TEXCOORD_0 = (u U, 1 - v V): one texture tile per pattern period, glTF's t pointing down.
TEST(SurfaceExport, texcoordsRepeatTheTextureOncePerPatternPeriod) {
    const BaseMesh mesh = makePlane();
    const SurfaceExportOptions o = toTemp("repeat.glb", {5, 4});
    exportSurface(mesh, testImages(4, 4), o);
    const gltf::Document d = test::loadGltf(o.path);
    const gltf::Primitive p = d.primitives(0).at(0);
    const std::vector<double> st = test::readAttribute(d, p, "TEXCOORD_0");
    std::set<std::pair<long, long>> expected, got;
    for (const glm::dvec2& uv : mesh.uvs)
        expected.insert({std::lround(uv.x * 5 * 1e5), std::lround((1 - uv.y * 4) * 1e5)});
    for (size_t i = 0; i + 1 < st.size(); i += 2) got.insert({std::lround(st[i] * 1e5), std::lround(st[i + 1] * 1e5)});
    EXPECT_EQ(got, expected);
    fs::remove(o.path);
}

// A position with two UVs (the cylinder's seam) becomes two glTF vertices.
TEST(SurfaceExport, seamPositionsAreSplitPerUv) {
    const BaseMesh mesh = makeCylinder();
    const SurfaceExportOptions o = toTemp("seam.glb");
    const SurfaceExportStats s = exportSurface(mesh, testImages(4, 4), o);
    EXPECT_GT(s.vertices, mesh.positions.size());
    EXPECT_EQ(s.triangles, mesh.faces.size());
    test::expectGltfValid(o.path);
    fs::remove(o.path);
}

// The plane has u along +x and v along -z with normal +y: TANGENT (1, 0, 0, +1), so
// w cross(NORMAL, TANGENT) = -z runs along increasing v (the normal map's +y).
TEST(SurfaceExport, tangentRunsAlongUAndBitangentAlongV) {
    SurfaceExportOptions o = toTemp("tangent.glb");
    exportSurface(makePlane(), testImages(2, 2), o);
    const gltf::Document d = test::loadGltf(o.path);
    const std::vector<double> t = test::readAttribute(d, d.primitives(0).at(0), "TANGENT");
    ASSERT_FALSE(t.empty());
    for (size_t i = 0; i + 3 < t.size(); i += 4) {
        EXPECT_NEAR(t[i], 1.0, 1e-6);
        EXPECT_NEAR(t[i + 1], 0.0, 1e-6);
        EXPECT_NEAR(t[i + 2], 0.0, 1e-6);
        EXPECT_EQ(t[i + 3], 1.0);
    }
    fs::remove(o.path);
}

TEST(SurfaceExport, nonGlbNameIsRefusedAndNoFileIsLeft) {
    const SurfaceExportOptions o = toTemp("surface.gltf");
    const std::string& path = o.path;
    const std::string e = test::errorOf([&] { exportSurface(makePlane(), testImages(4, 4), o); });
    EXPECT_NE(e.find(path), std::string::npos) << e;
    EXPECT_NE(e.find("GLB"), std::string::npos) << e;
    EXPECT_FALSE(fs::exists(path));
}

TEST(SurfaceExport, imagesNotMatchingTheirSizeAreRefused) {
    const SurfaceExportOptions o = toTemp("size.glb");
    SurfaceImages im = testImages(4, 4);
    im.normalRgb.pop_back();
    EXPECT_NE(test::errorOf([&] { exportSurface(makePlane(), im, o); }).find("4 x 4"), std::string::npos);
    EXPECT_FALSE(fs::exists(o.path));
}

TEST(SurfaceExport, blendModeIsWrittenWhenAsked) {
    SurfaceExportOptions o = toTemp("blend.glb");
    o.alphaMode = SurfaceAlpha::Blend;
    exportSurface(makePlane(), testImages(2, 2), o);
    EXPECT_EQ(test::loadGltf(o.path).root()["materials"][0]["alphaMode"], "BLEND");
    fs::remove(o.path);
}

// A view's surface level beside its curves, in one file: the streamed plies as before plus one
// more node with the textured triangles; .gltf too; other formats refuse it and write nothing.
TEST(SurfaceExport, surfaceLayerGoesIntoTheCurveGltfBesideThePlies) {
    SurfaceLayer layer;
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 4;
    layer.mesh = meshSubset(makePlane(mo), {0, 1, 2, 3, 4});
    layer.images = testImages(8, 8);
    layer.material.repeats = {2, 2};
    MappedYarns yarns;
    const std::vector<glm::dvec3> row{{0, 0.001, 0}, {0.01, 0.001, 0}, {0.02, 0.001, 0.001}};
    yarns.curves.addCurve(row.data(), row.size(), false);
    yarns.normals.assign(row.size(), glm::dvec3(0, 1, 0));
    PlyOptions po;
    po.yarnRadius = 0.0005;
    const PlyGenerator gen(yarns, po);
    ExportInput in;
    in.plies = &gen;
    in.radius = gen.options().plyRadius;
    in.surface = &layer;
    for (const char* name : {"layer.glb", "layer.gltf"}) {
        ExportOptions o;
        o.path = tempGlb(name);
        const ExportStats s = exportCurves(in, o);
        EXPECT_EQ(s.curves, 2u);
        EXPECT_EQ(s.surfaceTriangles, 5u);
        EXPECT_EQ(s.surfaceVertices, layer.mesh.positions.size());  // the plane has no UV seam
        EXPECT_GT(s.imageBytes, 0u);
        test::expectGltfValid(o.path);
        const gltf::Document d = test::loadGltf(o.path);
        const nlohmann::json& j = d.root();
        ASSERT_EQ(j["materials"].size(), 2u);  // "yarn" and "knit surface"
        EXPECT_EQ(j["materials"][1]["name"], "knit surface");
        EXPECT_EQ(j["images"].size(), 2u);
        size_t lines = 0, triangles = 0;
        for (const auto& mesh : j["meshes"])
            for (const auto& prim : mesh["primitives"]) {
                const int mode = prim.value("mode", 4);
                if (mode == 3) ++lines;
                if (mode == 4) {
                    ++triangles;
                    EXPECT_EQ(prim["material"], 1);
                    EXPECT_TRUE(prim["attributes"].contains("TEXCOORD_0"));
                }
            }
        EXPECT_EQ(lines, 2u);
        EXPECT_EQ(triangles, 1u);
        EXPECT_EQ(j["nodes"][0]["children"].size(), s.chunks + 1);  // the chunks, then the surface
        fs::remove(o.path);
        fs::remove(tempGlb("layer.bin"));
    }
    ExportOptions obj;
    obj.path = tempGlb("layer.obj");
    EXPECT_NE(test::errorOf([&] { exportCurves(in, obj); }).find("surface level"), std::string::npos);
    EXPECT_FALSE(fs::exists(obj.path));
}

}  // namespace
}  // namespace knit
