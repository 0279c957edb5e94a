// glTF 2.0 / GLB export: Khronos validator, round trip through the library's glTF reader, precision far from the origin,
// chunking into several buffers, per-yarn colours, KHR_mesh_quantization.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <tbb/global_control.h>

#include "export/export_helpers.hpp"
#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/plies.hpp"
#include "knit/sweep.hpp"

namespace knit {
namespace {

ExportStats write(const Polylines& c, double radius, ExportOptions o, const std::vector<uint32_t>* yarns = nullptr,
                  const std::string& materialExtrasJson = "") {
    return test::exportWith(c, radius, std::move(o), yarns, materialExtrasJson);
}

ExportOptions tubes(const std::string& path, int sides = 8) { return test::tubeOptions(path, sides); }

// Per curve, the ring centres of its tube vertices in sweep order (documented layout: rings of
// sides + 1 vertices, closed curves one extra ring = first point, then two caps).
std::vector<glm::dvec3> ringCentres(const Polylines& c, size_t curve, int sides, bool caps) {
    std::vector<glm::dvec3> out;
    const uint32_t n = c.size(curve);
    const bool closed = c.isClosed(curve);
    const size_t rings = closed ? n + 1 : n;
    for (size_t i = 0; i < rings; ++i)
        for (int j = 0; j <= sides; ++j) out.push_back(c.points[c.begin(curve) + i % n]);
    if (!closed && caps)
        for (int end = 0; end < 2; ++end)
            for (int j = 0; j <= sides; ++j) out.push_back(c.points[end == 0 ? c.begin(curve) : c.end(curve) - 1]);
    return out;
}

// Reads every tube vertex back (world positions, normals) in file order.
struct TubeRead {
    std::vector<glm::dvec3> positions, normals;
    std::vector<glm::dvec4> tangents;
    std::vector<glm::dvec2> uvs;
    std::vector<glm::dvec4> colours;
    size_t primitives = 0;
};

TubeRead readTubes(const gltf::Document& m) {
    TubeRead r;
    for (const auto& inst : m.meshInstances()) {
        for (const auto& p : m.primitives(inst.mesh)) {
            EXPECT_EQ(p.mode, size_t(gltf::kTriangles));
            ++r.primitives;
            const auto pos = test::worldPositions(m, p, inst.world);
            r.positions.insert(r.positions.end(), pos.begin(), pos.end());
            const auto n = test::readAttribute(m, p, "NORMAL");
            for (size_t i = 0; i + 2 < n.size(); i += 3) r.normals.emplace_back(n[i], n[i + 1], n[i + 2]);
            const auto t = test::readAttribute(m, p, "TANGENT");
            for (size_t i = 0; i + 3 < t.size(); i += 4) r.tangents.emplace_back(t[i], t[i + 1], t[i + 2], t[i + 3]);
            const auto uv = test::readAttribute(m, p, "TEXCOORD_0");
            for (size_t i = 0; i + 1 < uv.size(); i += 2) r.uvs.emplace_back(uv[i], uv[i + 1]);
            if (m.attribute(p, "COLOR_0")) {
                const auto c = test::readAttribute(m, p, "COLOR_0");
                for (size_t i = 0; i + 3 < c.size(); i += 4) r.colours.emplace_back(c[i], c[i + 1], c[i + 2], c[i + 3]);
            }
        }
    }
    return r;
}

// Side vertices satisfy position = centre + radius * normal; returns the worst deviation.
double worstRingError(const Polylines& c, const TubeRead& r, double radius, int sides, bool caps) {
    std::vector<glm::dvec3> centres;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        const auto rc = ringCentres(c, k, sides, caps);
        centres.insert(centres.end(), rc.begin(), rc.end());
    }
    EXPECT_EQ(centres.size(), r.positions.size());
    double worst = 0;
    size_t at = 0;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        const uint32_t n = c.size(k);
        const size_t ringVerts = (c.isClosed(k) ? n + 1 : n) * size_t(sides + 1);
        const size_t total = ringVerts + ((!c.isClosed(k) && caps) ? 2 * size_t(sides + 1) : 0);
        for (size_t i = 0; i < ringVerts && at + i < r.positions.size(); ++i) {
            const glm::dvec3 expect = centres[at + i] + radius * r.normals[at + i];
            worst = std::max(worst, glm::length(r.positions[at + i] - expect));
        }
        at += total;
    }
    return worst;
}

TEST(GltfExport, tubeGlbPassesValidatorAndRoundTrips) {
    const std::string dir = test::scratchDir("gltf_tubes_glb");
    const Polylines c = test::mixedCurves();
    const double radius = 0.0015;
    const ExportStats s = write(c, radius, tubes(dir + "/tubes.glb"));
    EXPECT_EQ(s.format, "glb");
    EXPECT_EQ(s.chunks, 1u);
    EXPECT_EQ(s.buffers, 1u);
    EXPECT_EQ(s.vertices, (42 + 33 + 27) * 9u);
    test::expectGltfValid(dir + "/tubes.glb");

    const gltf::Document m = test::loadGltf(dir + "/tubes.glb");
    ASSERT_EQ(m.extensionsUsed(), std::vector<std::string>{"KHR_materials_sheen"});
    const TubeRead r = readTubes(m);
    ASSERT_EQ(r.positions.size(), s.vertices);
    EXPECT_LT(worstRingError(c, r, radius, 8, true), 1e-6 * radius * 10);
    for (size_t i = 0; i < r.normals.size(); ++i) {
        ASSERT_NEAR(glm::length(r.normals[i]), 1.0, 1e-6) << i;
        ASSERT_NEAR(glm::length(glm::dvec3(r.tangents[i])), 1.0, 1e-6) << i;
        ASSERT_EQ(std::abs(r.tangents[i].w), 1.0) << i;
        ASSERT_GE(r.uvs[i].x, 0.0);
        ASSERT_LE(r.uvs[i].x, 1.0);
    }
    // The material carries KHR_materials_sheen and the radius in extras.
    const nlohmann::json& materials = m.root().at("materials");
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_TRUE(materials[0].at("extensions").contains("KHR_materials_sheen"));
    EXPECT_DOUBLE_EQ(materials[0].at("extras").at("radius").get<double>(), radius);
}

TEST(GltfExport, materialExtrasTextReachesTheMaterial) {
    const std::string dir = test::scratchDir("gltf_extras");
    ExportOptions o;
    o.path = dir + "/extras.gltf";
    o.what = ExportWhat::Yarns;
    write(test::mixedCurves(), 0.001, o, nullptr,
          R"({"generator": "test", "weights": [1, 2.5], "nested": {"on": true}})");
    test::expectGltfValid(o.path);
    const gltf::Document m = test::loadGltf(o.path);
    const nlohmann::json& extras = m.root().at("materials").at(0).at("extras");
    EXPECT_EQ(extras.at("generator"), "test");
    EXPECT_EQ(extras.at("weights"), nlohmann::json::parse("[1, 2.5]"));
    EXPECT_EQ(extras.at("nested").at("on"), true);
    EXPECT_DOUBLE_EQ(extras.at("radius").get<double>(), 0.001);  // added by the exporter
}

TEST(GltfExport, tubeGltfWritesExternalBinAndPassesValidator) {
    const std::string dir = test::scratchDir("gltf_tubes_text");
    const Polylines c = test::mixedCurves();
    write(c, 0.001, tubes(dir + "/my tubes.gltf", 5));
    auto files = test::listDir(dir);
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"my tubes.bin", "my tubes.gltf"}));
    test::expectGltfValid(dir + "/my tubes.gltf");
    const gltf::Document m = test::loadGltf(dir + "/my tubes.gltf");
    ASSERT_EQ(m.bufferCount(), 1u);
    EXPECT_EQ(m.root()["buffers"][0].at("uri"), "my%20tubes.bin");
    const TubeRead r = readTubes(m);
    EXPECT_LT(worstRingError(c, r, 0.001, 5, true), 1e-8);
}

TEST(GltfExport, curvesAreOneNonIndexedLineStripPerCurveWithRadius) {
    const std::string dir = test::scratchDir("gltf_curves");
    const Polylines c = test::mixedCurves(glm::dvec3(3, -2, 1));
    ExportOptions o;
    o.path = dir + "/curves.glb";
    o.what = ExportWhat::Plies;
    const ExportStats s = write(c, 0.0007, o);
    EXPECT_EQ(s.curves, 3u);
    EXPECT_EQ(s.vertices, c.pointCount());
    test::expectGltfValid(dir + "/curves.glb");
    const gltf::Document m = test::loadGltf(dir + "/curves.glb");
    const auto inst = m.meshInstances();
    ASSERT_EQ(inst.size(), 1u);
    const auto prims = m.primitives(inst[0].mesh);
    ASSERT_EQ(prims.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(prims[k].mode, size_t(gltf::kLineStrip));
        EXPECT_FALSE(m.indices(prims[k])) << "curve " << k;
        const auto pos = test::worldPositions(m, prims[k], inst[0].world);
        const auto rad = test::readAttribute(m, prims[k], "_RADIUS");
        const size_t n = c.size(k);
        // A closed curve repeats its first point at the end.
        ASSERT_EQ(pos.size(), c.isClosed(k) ? n + 1 : n) << "curve " << k;
        ASSERT_EQ(rad.size(), pos.size()) << "curve " << k;
        if (c.isClosed(k)) EXPECT_EQ(pos.front(), pos.back());
        for (size_t i = 0; i < n; ++i) {
            EXPECT_LT(glm::length(pos[i] - c.points[c.begin(k) + i]), 1e-6) << "curve " << k << " point " << i;
            EXPECT_FLOAT_EQ(float(rad[i]), 0.0007f);
        }
    }
}

TEST(GltfExport, planeHundredKilometresFromOriginKeepsSubMilliRadiusPrecision) {
    const std::string dir = test::scratchDir("gltf_far");
    const double radius = 0.001;
    const glm::dvec3 far(100000.0, 25000.0, -3000.0);
    const Polylines c = test::planeRows(6, 120, 0.002, far, 0.0015);
    // Curves: every point back within 1e-3 yarn radii.
    ExportOptions o;
    o.path = dir + "/far_curves.glb";
    o.what = ExportWhat::Yarns;
    o.chunkVertices = 300;  // several chunks, each with its own origin
    const ExportStats cs = write(c, radius, o);
    EXPECT_GE(cs.chunks, 2u);
    test::expectGltfValid(o.path);
    const double worst = test::worstCurveDeviation(test::loadGltf(o.path), c);
    EXPECT_LT(worst, 1e-3 * radius);

    // Tubes: every side vertex = centre + radius * normal within 1e-3 yarn radii.
    ExportOptions t = tubes(dir + "/far_tubes.glb", 6);
    t.chunkVertices = 2000;
    write(c, radius, t);
    test::expectGltfValid(t.path);
    const TubeRead r = readTubes(test::loadGltf(t.path));
    EXPECT_LT(worstRingError(c, r, radius, 6, true), 1e-3 * radius);
}

TEST(GltfExport, smallBufferLimitSplitsIntoSeveralBuffers) {
    const std::string dir = test::scratchDir("gltf_buffers");
    const Polylines c = test::planeRows(10, 200, 0.002, glm::dvec3(0), 0.001);
    ExportOptions o = tubes(dir + "/split.glb", 6);
    o.chunkVertices = 1500;
    o.maxBufferBytes = 200000;
    const ExportStats s = write(c, 0.001, o);
    EXPECT_GE(s.buffers, 3u);
    EXPECT_TRUE(std::filesystem::exists(dir + "/split_1.bin"));
    test::expectGltfValid(o.path);
    const gltf::Document m = test::loadGltf(o.path);
    ASSERT_EQ(m.bufferCount(), s.buffers);
    for (size_t b = 0; b < m.bufferCount(); ++b) EXPECT_LE(m.buffer(b, "test").size(), 200000u);
    const TubeRead r = readTubes(m);
    EXPECT_EQ(r.positions.size(), s.vertices);
    // float32 offsets over chunks of ~0.4 m: ~2.4e-8 m rounding.
    EXPECT_LT(worstRingError(c, r, 0.001, 6, true), 6e-8);
}

TEST(GltfExport, yarnColoursAreConstantPerYarnAndDistinctBetweenYarns) {
    const std::string dir = test::scratchDir("gltf_colours");
    const Polylines c = test::mixedCurves();
    const std::vector<uint32_t> yarnOf{0, 1, 0};  // curves 0 and 2 are plies of yarn 0
    ExportOptions o = tubes(dir + "/colours.glb", 4);
    o.yarnColors = true;
    write(c, 0.001, o, &yarnOf);
    test::expectGltfValid(o.path);
    const TubeRead r = readTubes(test::loadGltf(o.path));
    ASSERT_EQ(r.colours.size(), r.positions.size());
    const size_t n0 = (40 + 2) * 5, n1 = (32 + 1) * 5;
    const glm::dvec4 a = r.colours.front(), b = r.colours[n0], last = r.colours.back();
    for (size_t i = 0; i < n0; ++i) ASSERT_EQ(r.colours[i], a) << i;
    for (size_t i = n0; i < n0 + n1; ++i) ASSERT_EQ(r.colours[i], b) << i;
    EXPECT_EQ(last, a);
    EXPECT_NE(a, b);
    EXPECT_EQ(a.w, 1.0);
}

TEST(GltfExport, quantizedMeshIsRequiredExtensionAndRoundTripsWithinStep) {
    const std::string dir = test::scratchDir("gltf_quantized");
    const Polylines c = test::mixedCurves(glm::dvec3(-50.0, 10.0, 2.0));
    const double radius = 0.001;
    ExportOptions o = tubes(dir + "/q.glb", 8);
    o.quantize = true;
    const ExportStats s = write(c, radius, o);
    EXPECT_LT(s.compressedMeshBytes, s.uncompressedMeshBytes);
    test::expectGltfValid(o.path);
    const gltf::Document m = test::loadGltf(o.path);
    const std::vector<std::string> required = m.extensionsRequired();
    EXPECT_NE(std::find(required.begin(), required.end(), "KHR_mesh_quantization"), required.end());
    const TubeRead r = readTubes(m);
    ASSERT_EQ(r.positions.size(), s.vertices);
    // int16 over the chunk's extent (~0.1 m): step ~1.5e-6 m; normals to 1/32767.
    EXPECT_LT(worstRingError(c, r, radius, 8, true), 5e-6);
    for (size_t i = 0; i < r.normals.size(); ++i) {
        ASSERT_NEAR(glm::length(r.normals[i]), 1.0, 1e-4);
        ASSERT_EQ(std::abs(r.tangents[i].w), 1.0);
    }
}

TEST(GltfExport, jsonLargerThanReservationRewritesAValidGlb) {
    const std::string dir = test::scratchDir("gltf_reserve");
    const Polylines c = test::mixedCurves();
    ExportOptions o = tubes(dir + "/small_reserve.glb", 6);
    o.glbJsonReserve = 64;  // far too small: the writer must fall back to copying the BIN data
    const ExportStats s = write(c, 0.001, o);
    ExportOptions p = tubes(dir + "/auto_reserve.glb", 6);
    write(c, 0.001, p);
    EXPECT_EQ(test::listDir(dir).size(), 2u) << "no temporary file left";
    test::expectGltfValid(o.path);
    const TubeRead a = readTubes(test::loadGltf(o.path)), b = readTubes(test::loadGltf(p.path));
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(s.bytes, test::readBytes(o.path).size());
}

TEST(GltfExport, glbIsByteIdenticalForOneAndManyThreads) {
    const std::string dir = test::scratchDir("gltf_threads");
    Polylines c;
    for (int k = 0; k < 40; ++k) {
        const auto h = test::helix(80, 0.004, 0.002, 3.0, glm::dvec3(0.01 * k, 0, 0));
        c.addCurve(h.data(), h.size(), k % 4 == 0);
    }
    ExportOptions o = tubes(dir + "/one.glb", 7);
    o.chunkVertices = 3000;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        write(c, 0.0005, o);
    }
    ExportOptions m = o;
    m.path = dir + "/many.glb";
    write(c, 0.0005, m);
    EXPECT_EQ(test::readBytes(o.path), test::readBytes(m.path));
}

TEST(GltfExport, emptyCurveSetWritesValidEmptyScene) {
    const std::string dir = test::scratchDir("gltf_empty");
    const Polylines c;
    ExportOptions o = tubes(dir + "/empty.glb");
    const ExportStats s = write(c, 0.001, o);
    EXPECT_EQ(s.vertices, 0u);
    test::expectGltfValid(o.path);
}

// Export input for plies generated (and streamed) by `gen`.
ExportInput streamed(const PlyGenerator& gen) {
    ExportInput in;
    in.plies = &gen;
    in.radius = gen.options().plyRadius;
    return in;
}

// Plies streamed from a PlyGenerator: the file depends on neither the thread count nor the
// pipeline's timing (chunks are written in order), and yarns without plies are skipped.
TEST(GltfExport, streamedPliesAreTheSameFileForAnyThreadCount) {
    const std::string dir = test::scratchDir("gltf_streamed_threads");
    MappedYarns yarns;
    yarns.curves = test::planeRows(12, 90, 0.0015, glm::dvec3(2, 1, -1), 0.001);
    const auto loop = test::circle(40, 0.01, glm::dvec3(2, 1.1, -1));
    yarns.curves.addCurve(loop.data(), loop.size(), true);
    const glm::dvec3 lone(5, 5, 5);
    yarns.curves.addCurve(&lone, 1, false);  // one point: no plies
    yarns.normals.assign(yarns.curves.pointCount(), glm::dvec3(0, 0, 1));
    PlyOptions po;
    po.count = 3;
    po.yarnRadius = 0.0004;
    const PlyGenerator gen(yarns, po);
    const ExportInput in = streamed(gen);
    ExportOptions o;
    o.what = ExportWhat::Plies;
    o.chunkVertices = 700;  // many chunks in flight
    o.path = dir + "/one.glb";
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        exportCurves(in, o);
    }
    o.path = dir + "/all.glb";
    const ExportStats s = exportCurves(in, o);
    EXPECT_EQ(s.curves, 13u * 3u);
    EXPECT_GE(s.chunks, 5u);
    EXPECT_EQ(test::readBytes(dir + "/one.glb"), test::readBytes(dir + "/all.glb"));
    test::expectGltfValid(o.path);
    const Plies all = makePlies(gen);
    EXPECT_EQ(s.vertices, all.curves.pointCount());
    EXPECT_LT(test::worstCurveDeviation(test::loadGltf(o.path), all.curves), 1e-3 * all.plyRadius);
}

TEST(GltfExport, streamedPliesOfNoYarnsWriteAValidEmptyScene) {
    const std::string dir = test::scratchDir("gltf_streamed_empty");
    MappedYarns none, degenerate;
    const glm::dvec3 p(1, 2, 3);
    degenerate.curves.addCurve(&p, 1, false);
    for (const MappedYarns* yarns : {&none, &degenerate}) {
        PlyOptions po;
        po.yarnRadius = 0.001;
        const PlyGenerator gen(*yarns, po);
        const ExportInput in = streamed(gen);
        for (const char* name : {"/empty.glb", "/empty.gltf"}) {
            ExportOptions o;
            o.what = ExportWhat::Plies;
            o.path = dir + name;
            const ExportStats s = exportCurves(in, o);
            EXPECT_EQ(s.curves, 0u);
            EXPECT_EQ(s.vertices, 0u);
            test::expectGltfValid(o.path);
        }
    }
}

// A streamed yarn whose plies could not fit one batch (32-bit offsets) is refused before anything
// is written, naming the output, instead of failing deep in the pipeline.
TEST(GltfExport, streamedPliesOfAnAbsurdPitchAreRefusedUpFront) {
    const std::string dir = test::scratchDir("gltf_streamed_absurd");
    MappedYarns yarns;
    const glm::dvec3 line[2] = {glm::dvec3(0), glm::dvec3(1, 0, 0)};
    yarns.curves.addCurve(line, 2, false);
    PlyOptions po;
    po.yarnRadius = 0.001;
    po.pitch = 1e-8;  // 1 m of yarn at 12 samples per 10 nm: ~2.4e9 ply points
    const PlyGenerator gen(yarns, po);
    const ExportInput in = streamed(gen);
    ExportOptions o;
    o.what = ExportWhat::Plies;
    o.path = dir + "/absurd.glb";
    try {
        exportCurves(in, o);
        FAIL() << "expected knit::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(o.path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("ply pitch"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(test::listDir(dir).empty());
}

}  // namespace
}  // namespace knit
