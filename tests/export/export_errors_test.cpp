// Bad input: unknown extension, unwritable paths, conflicting options, bad data — a clear
// knit::Error and no file (not even a temporary one) left behind. Also exportScene's choice of
// curves.
#include <gtest/gtest.h>

#include <utility>

#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"
#include "knit/export.hpp"
#include "knit/sweep.hpp"

namespace knit {
namespace {

std::string errorOf(const Polylines& c, const ExportOptions& o, double radius = 0.001,
                    const std::string& materialExtrasJson = "") {
    ExportInput in;
    in.curves = &c;
    in.radius = radius;
    in.materialExtrasJson = materialExtrasJson;
    try {
        exportCurves(in, o);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(ExportErrors, unknownExtensionListsSupportedFormats) {
    const std::string dir = test::scratchDir("err_ext");
    ExportOptions o;
    o.path = dir + "/out.stl";
    const std::string e = errorOf(test::mixedCurves(), o);
    EXPECT_TRUE(contains(e, "unknown extension '.stl'")) << e;
    for (const char* ext : {".obj", ".ply", ".bcc", ".pbrt", ".gltf", ".glb"}) EXPECT_TRUE(contains(e, ext)) << e;
    o.path = dir + "/noextension";
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o), "unknown extension")) << e;
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportErrors, dracoWithCurvesIsRefused) {
    const std::string dir = test::scratchDir("err_draco_curves");
    ExportOptions o;
    o.path = dir + "/c.glb";
    o.what = ExportWhat::Plies;
    o.draco = true;
    const std::string e = errorOf(test::mixedCurves(), o);
    EXPECT_TRUE(contains(e, "Draco compression applies to tube meshes only, not to curves")) << e;
    EXPECT_TRUE(contains(e, "what to export is plies, not tubes")) << e;
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportErrors, dracoOutsideGltfAndDracoWithQuantizeAreRefused) {
    const std::string dir = test::scratchDir("err_conflicts");
    ExportOptions o;
    o.what = ExportWhat::Tubes;
    o.draco = true;
    o.path = dir + "/t.obj";
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o), "needs a .glb or .gltf"));
    o.path = dir + "/t.glb";
    o.quantize = true;
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o), "Draco compression and mesh quantization"));
    o.draco = false;
    o.what = ExportWhat::Yarns;
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o), "tube meshes only"));
    o.what = ExportWhat::Tubes;
    o.quantize = false;
    o.sides = 2;
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o), "the number of tube sides must be in [3, 1024], got 2"));
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportErrors, missingFolderAndFileAsFolderNameThePath) {
    const std::string dir = test::scratchDir("err_paths");
    ExportOptions o;
    o.path = dir + "/missing/out.glb";
    std::string e = errorOf(test::mixedCurves(), o);
    EXPECT_TRUE(contains(e, o.path) && contains(e, "does not exist")) << e;
    // A regular file where a folder is expected.
    test::writeText(dir + "/file", "x");
    o.path = dir + "/file/out.obj";
    e = errorOf(test::mixedCurves(), o);
    EXPECT_TRUE(contains(e, o.path) && contains(e, "not a folder")) << e;
    // An existing folder as output.
    std::filesystem::create_directory(dir + "/folder.glb");
    o.path = dir + "/folder.glb";
    e = errorOf(test::mixedCurves(), o);
    EXPECT_TRUE(contains(e, "folder")) << e;
    auto files = test::listDir(dir);
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"file", "folder.glb"}));
}

TEST(ExportErrors, nonFinitePointNamesCurveAndPoint) {
    const std::string dir = test::scratchDir("err_nan");
    Polylines c = test::mixedCurves();
    c.points[c.begin(2) + 4].y = std::nan("");
    ExportOptions o;
    o.path = dir + "/x.glb";
    o.what = ExportWhat::Tubes;
    const std::string e = errorOf(c, o);
    EXPECT_TRUE(contains(e, "curve 2 point 4")) << e;
    EXPECT_TRUE(contains(errorOf(test::mixedCurves(), o, -1.0), "radius")) << "negative radius";
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportErrors, offsetsPastTheEndAreRefusedBeforeReading) {
    // Offsets {0, 10, 3, 6} over 6 points: curve 0 claims points 0..9. The 4 slots past the end
    // hold NaN (capacity kept after the resize), so reading them would report "curve 0 point 6
    // is not finite" instead of the offsets.
    const std::string dir = test::scratchDir("err_offsets");
    Polylines c;
    c.points.assign(10, glm::dvec3(std::nan("")));
    for (size_t i = 0; i < 6; ++i) c.points[i] = glm::dvec3(0.001 * double(i), 0, 0);
    c.points.resize(6);
    c.offsets = {0, 10, 3, 6};
    c.closed = {0, 0, 0};
    ExportOptions o;
    o.path = dir + "/x.obj";
    o.what = ExportWhat::Yarns;
    const std::string e = errorOf(c, o);
    EXPECT_EQ(e, "cannot export: curve 0 ends at offset 10, past the 6 points");
    EXPECT_TRUE(test::listDir(dir).empty());
    // Within the points but decreasing: named as before.
    c.offsets = {0, 4, 3, 6};
    EXPECT_EQ(errorOf(c, o), "cannot export: curve 1 has decreasing offsets");
}

TEST(ExportErrors, materialExtrasThatAreNotAJsonObjectAreRefused) {
    const std::string dir = test::scratchDir("err_extras");
    ExportOptions o;
    o.path = dir + "/x.glb";
    EXPECT_EQ(errorOf(test::mixedCurves(), o, 0.001, "[1, 2]"),
              "cannot export: the glTF material extras must be a JSON object");
    const std::string e = errorOf(test::mixedCurves(), o, 0.001, "{\"generator\": ");
    EXPECT_TRUE(contains(e, "cannot export: the glTF material extras are not valid JSON: ")) << e;
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportErrors, chunkLargerThanBufferLimitIsRefusedWithoutFiles) {
    const std::string dir = test::scratchDir("err_late");
    // Small curves first (chunks stream into buffers), then one curve too big for any buffer.
    Polylines c = test::planeRows(4, 50, 0.002, glm::dvec3(0), 0.001);
    const auto big = test::helix(4000, 0.01, 0.002, 40.0);
    c.addCurve(big.data(), big.size(), false);
    ExportOptions o;
    o.path = dir + "/late.gltf";
    o.what = ExportWhat::Tubes;
    o.chunkVertices = 500;
    o.maxBufferBytes = 100000;
    const std::string e = errorOf(c, o);
    EXPECT_TRUE(contains(e, "lower the vertices per chunk")) << e;
    EXPECT_TRUE(test::listDir(dir).empty()) << "left: " << (test::listDir(dir).empty() ? "" : test::listDir(dir)[0]);
}

TEST(ExportErrors, existingFileSurvivesFailedExport) {
    const std::string dir = test::scratchDir("err_keep");
    const Polylines c = test::mixedCurves();
    ExportOptions o;
    o.path = dir + "/keep.glb";
    o.what = ExportWhat::Tubes;
    ExportInput in;
    in.curves = &c;
    in.radius = 0.001;
    exportCurves(in, o);
    const auto before = test::readBytes(o.path);
    Polylines bad = c;
    bad.points[3].x = INFINITY;
    in.curves = &bad;
    EXPECT_THROW(exportCurves(in, o), Error);
    EXPECT_EQ(test::readBytes(o.path), before);
    EXPECT_EQ(test::listDir(dir).size(), 1u);
}

// ---- exportScene: which curves, which radius ----
Scene syntheticScene(bool withPlies) {
    SceneParts s;
    s.yarnRadius = 0.002;
    s.yarns.curves = test::mixedCurves();
    s.yarns.normals.assign(s.yarns.curves.pointCount(), glm::dvec3(0, 0, 1));
    if (withPlies) {
        for (size_t k = 0; k < 3; ++k) {
            const auto h = test::helix(30, 0.001, 0.002, 2.0, glm::dvec3(0.1 * k, 0, 0));
            s.plies.curves.addCurve(h.data(), h.size(), false);
            s.plies.yarnOfCurve.push_back(uint32_t(k / 2));
            s.plies.plyOfCurve.push_back(uint8_t(k % 2));
        }
        s.plies.plyRadius = 0.0008;
        s.plies.centerRadius = 0.0011;
        s.plies.pitch = 0.012;
        s.plies.radial.assign(s.plies.curves.pointCount(), glm::dvec3(1, 0, 0));
    }
    return Scene::fromParts(std::move(s));
}

TEST(ExportScene, pliesYarnsAndTubesPickTheRightCurves) {
    const std::string dir = test::scratchDir("scene");
    const Scene s = syntheticScene(true);
    ExportOptions o;
    o.path = dir + "/p.bcc";
    o.what = ExportWhat::Plies;
    EXPECT_EQ(exportScene(s, o).vertices, s.plies().curves.pointCount());
    o.what = ExportWhat::Yarns;
    o.path = dir + "/y.bcc";
    EXPECT_EQ(exportScene(s, o).vertices, s.yarns().curves.pointCount());
    o.what = ExportWhat::Tubes;
    o.path = dir + "/t.obj";
    o.sides = 4;
    EXPECT_EQ(exportScene(s, o).vertices, 3 * tubeVertexCount(30, false, TubeOptions{4, true, nullptr}));
    o.tubesOf = TubeSource::Yarns;
    EXPECT_EQ(exportScene(s, o).curves, 3u);
    EXPECT_EQ(exportScene(s, o).vertices, (42 + 33 + 27) * 5u);
}

// What no file should hold is refused by exportScene itself, for every caller (the CLI, Python,
// C++), naming why, before anything is written.
TEST(ExportScene, emptyResultIsRefusedNamingWhyAndWritesNothing) {
    const std::string dir = test::scratchDir("scene_empty");
    SceneOptions so;
    so.mesh = "plane";
    so.placement.repeats = {1e-6, 1e-6};  // no pattern period fits the mesh: no yarn lands on it
    const Scene none = buildScene(so);
    ASSERT_EQ(none.yarns().curves.pointCount(), 0u);
    ExportOptions o;
    for (const ExportWhat what : {ExportWhat::Yarns, ExportWhat::Plies, ExportWhat::Tubes})
        for (const char* name : {"/e.obj", "/e.glb", "/e.bcc"}) {
            o.what = what;
            o.path = dir + name;
            if (what == ExportWhat::Tubes && o.path.back() == 'c') continue;  // .bcc holds no tubes
            const std::string e = test::errorOf([&] { exportScene(none, o); });
            EXPECT_TRUE(contains(e, "nothing to export: no yarn of pattern 'stockinette' lands on mesh 'plane'")) << e;
            EXPECT_TRUE(contains(e, "; no file written")) << e;
        }
    // Yarns, but a ply pitch longer than every yarn: no ply curve.
    so.placement.repeats = {3, 3};
    so.plies.pitch = 1e30;
    const Scene noPlies = buildScene(so);
    ASSERT_GT(noPlies.yarns().curves.pointCount(), 0u);
    o.what = ExportWhat::Plies;
    o.path = dir + "/p.glb";
    const std::string e = test::errorOf([&] { exportScene(noPlies, o); });
    EXPECT_TRUE(contains(e, "nothing to export: every yarn is shorter than one ply sample")) << e;
    o.what = ExportWhat::Yarns;  // the yarns are there
    o.path = dir + "/y.obj";
    EXPECT_GT(exportScene(noPlies, o).curves, 0u);
    std::filesystem::remove(o.path);
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(ExportScene, valuesBeyondFloat32AreRefusedNamingTheValue) {
    const std::string dir = test::scratchDir("scene_float32");
    SceneOptions so;
    so.mesh = "plane";
    so.placement.repeats = {3, 3};
    so.plies.pitch = 1e39;  // a double, beyond any float32
    so.buildPlies = false;
    const Scene far = buildScene(so);
    ExportOptions o;
    o.path = dir + "/p.obj";  // every format refuses radii and pitch beyond float32
    std::string e = test::errorOf([&] { exportScene(far, o); });
    EXPECT_TRUE(contains(e, "cannot write '" + o.path + "': the ply pitch 1e+39 is beyond the float32 range")) << e;
    o.what = ExportWhat::Yarns;  // no plies written: the pitch does not matter
    EXPECT_GT(exportScene(far, o).curves, 0u);
    std::filesystem::remove(o.path);

    // Coordinates: refused for a float32 format, kept in double precision by .obj.
    SceneParts parts;
    parts.yarnRadius = 0.002;
    parts.yarns.curves = test::mixedCurves();
    parts.yarns.curves.points[0].x = 5e38;
    const Scene huge = Scene::fromParts(std::move(parts));
    o.path = dir + "/y.glb";
    e = test::errorOf([&] { exportScene(huge, o); });
    EXPECT_TRUE(contains(e, "cannot write '" + o.path + "': a coordinate of the curves 5e+38 is beyond the float32"))
        << e;
    o.path = dir + "/y.obj";
    EXPECT_GT(exportScene(huge, o).curves, 0u);
    std::filesystem::remove(o.path);
    EXPECT_TRUE(test::listDir(dir).empty());
}

// A scene built without plies still exports plies: generated while writing (streamed into
// glTF/GLB, generated in full for other formats), the same curves a scene with plies holds.
TEST(ExportScene, pliesOfASceneBuiltWithoutPliesAreGeneratedWhileWriting) {
    const std::string dir = test::scratchDir("scene_streamed");
    SceneOptions so;
    so.mesh = "cylinder";
    so.placement.repeats = {9, 5};
    const Scene built = buildScene(so);
    so.buildPlies = false;
    const Scene bare = buildScene(so);
    ASSERT_GT(built.plies().curves.curveCount(), 4u);
    ASSERT_EQ(bare.plies().curves.curveCount(), 0u);

    ExportOptions o;
    o.what = ExportWhat::Plies;
    o.chunkVertices = 3000;  // several chunks, split differently in the two paths
    o.path = dir + "/built.glb";
    const ExportStats a = exportScene(built, o);
    o.path = dir + "/streamed.glb";
    const ExportStats b = exportScene(bare, o);
    EXPECT_EQ(a.curves, built.plies().curves.curveCount());
    EXPECT_EQ(b.curves, a.curves);
    EXPECT_EQ(b.vertices, built.plies().curves.pointCount());
    EXPECT_GE(b.chunks, 3u);
    test::expectGltfValid(o.path);
    const double worst = test::worstCurveDeviation(test::loadGltf(o.path), built.plies().curves);
    EXPECT_LT(worst, 1e-3 * built.plies().plyRadius);  // float32 relative to each chunk's origin

    // Non-glTF formats generate the plies in full first: the same file as from the built plies.
    o.path = dir + "/built.bcc";
    exportScene(built, o);
    o.path = dir + "/streamed.bcc";
    exportScene(bare, o);
    EXPECT_EQ(test::readBytes(dir + "/built.bcc"), test::readBytes(dir + "/streamed.bcc"));

    // Bad ply settings are reported before any file is written.
    so.plies.samplesPerTurn = 2;  // kept unchecked in a scene built without plies
    const Scene broken = buildScene(so);
    o.path = dir + "/broken.glb";
    try {
        exportScene(broken, o);
        FAIL() << "expected knit::Error";
    } catch (const Error& e) {
        EXPECT_TRUE(contains(e.what(), "the samples per turn")) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(o.path));
    o.what = ExportWhat::Tubes;  // auto: the yarns of a scene without plies, but plies were asked for
    o.path = dir + "/tubes.obj";
    EXPECT_TRUE(contains(test::errorOf([&] { exportScene(broken, o); }), "the samples per turn"));
    o.what = ExportWhat::Yarns;
    o.path = dir + "/yarns.obj";
    EXPECT_EQ(exportScene(broken, o).curves, broken.yarns().curves.curveCount());
}

}  // namespace
}  // namespace knit
