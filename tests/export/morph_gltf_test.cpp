// One animated GLB (knit/morph_gltf.hpp): the first frame plus a morph target per frame, an
// animation whose weights select frame k at time k / fps; checked by the Khronos validator and
// read back with the project's glTF reader.
#include <gtest/gtest.h>

#include <filesystem>

#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/morph_gltf.hpp"
#include "knit/sweep.hpp"

namespace knit {
namespace {

// Frame k of a small animation: the curves far from the origin, swirled by k (every point moves
// differently, so a wrong target or offset shows).
std::vector<glm::dvec3> framePoints(const Polylines& c, int k) {
    std::vector<glm::dvec3> p = c.points;
    for (size_t i = 0; i < p.size(); ++i)
        p[i] =
            glm::dvec3(5000.0, -20.0, 100.0) + p[i] * (1.0 + 0.1 * k) + glm::dvec3(0.0, 0.002 * k * double(i % 7), 0.0);
    return p;
}

// Positions of morph target `t` of the only primitive applied at weight 1, in world space.
std::vector<glm::dvec3> morphedPositions(const gltf::Document& d, size_t t) {
    const gltf::MeshInstance inst = d.meshInstances().at(0);
    const gltf::Primitive prim = d.primitives(inst.mesh).at(0);
    std::vector<glm::dvec3> p = test::worldPositions(d, prim, inst.world);
    const size_t a = (*prim.object)["targets"][t]["POSITION"].get<size_t>();
    const std::vector<double> delta = test::readAccessor(d, a);
    for (size_t i = 0; i < p.size(); ++i) p[i] += glm::dvec3(delta[3 * i], delta[3 * i + 1], delta[3 * i + 2]);
    return p;
}

TEST(MorphGlb, morphTargetKWithWeightOneReproducesFrameK) {
    const std::string path = test::scratchDir("morph_glb_curves") + "/a.glb";
    const Polylines c = test::mixedCurves();
    const int frames = 4;
    MorphTopology base;
    base.positions = framePoints(c, 0);
    base.indices = segmentIndices(c.offsets, c.closed);
    base.radius = 0.001;
    MorphGlbOptions o;
    o.fps = 12;
    MorphGlbWriter w(path, base, frames, o);
    for (int k = 0; k < frames; ++k) w.writeFrame(framePoints(c, k));
    w.commit();
    test::expectGltfValid(path);
    const gltf::Document d = test::loadGltf(path);
    for (int k = 0; k < frames; ++k) {
        const std::vector<glm::dvec3> want = framePoints(c, k), got = morphedPositions(d, size_t(k));
        ASSERT_EQ(got.size(), want.size());
        for (size_t i = 0; i < want.size(); ++i)
            ASSERT_LE(glm::length(got[i] - want[i]), 2e-6) << "frame " << k << " point " << i;
    }
    // The animation: times k / fps, one-hot weights, STEP, on the mesh's node.
    const nlohmann::json& anim = d.root()["animations"][0];
    EXPECT_EQ(anim["samplers"][0]["interpolation"], "STEP");
    EXPECT_EQ(anim["channels"][0]["target"]["path"], "weights");
    const std::vector<double> t = test::readAccessor(d, anim["samplers"][0]["input"].get<size_t>());
    const std::vector<double> wts = test::readAccessor(d, anim["samplers"][0]["output"].get<size_t>());
    ASSERT_EQ(t.size(), size_t(frames));
    ASSERT_EQ(wts.size(), size_t(frames * frames));
    for (int k = 0; k < frames; ++k) {
        EXPECT_FLOAT_EQ(t[size_t(k)], float(k / 12.0));
        for (int j = 0; j < frames; ++j) EXPECT_EQ(wts[size_t(k * frames + j)], j == k ? 1.0 : 0.0);
    }
    // The lines: every segment of the curves, the closed circle's closing segment included.
    const size_t segments = 39 + 32 + 24;
    EXPECT_EQ(test::readAccessor(d, *d.indices(d.primitives(0).at(0))).size(), 2 * segments);
}

TEST(MorphGlb, tubeFramesCarryNormalTargetsAndPassTheValidator) {
    const std::string path = test::scratchDir("morph_glb_tubes") + "/t.glb";
    const Polylines c = test::mixedCurves();
    TubeOptions to;
    std::vector<TubeMesh> meshes;
    Polylines f = c;
    for (int k = 0; k < 3; ++k) {
        f.points = framePoints(c, k);
        meshes.push_back(sweepTubes(f, 0.001, to, 0, f.curveCount(), glm::dvec3(5000.0, -20.0, 100.0)));
    }
    auto doubles = [](const TubeMesh& m) {
        std::vector<glm::dvec3> p;
        for (const glm::vec3& v : m.positions) p.push_back(m.origin + glm::dvec3(v));
        return p;
    };
    MorphTopology base;
    base.triangles = true;
    base.positions = doubles(meshes[0]);
    base.normals = meshes[0].normals;
    for (const glm::uvec3& t : meshes[0].triangles) base.indices.insert(base.indices.end(), {t.x, t.y, t.z});
    MorphGlbOptions o;
    o.linear = true;
    MorphGlbWriter w(path, base, 3, o);
    for (const TubeMesh& m : meshes) w.writeFrame(doubles(m), &m.normals);
    w.commit();
    test::expectGltfValid(path);
    const gltf::Document d = test::loadGltf(path);
    const std::vector<glm::dvec3> want = doubles(meshes[2]), got = morphedPositions(d, 2);
    for (size_t i = 0; i < want.size(); ++i) ASSERT_LE(glm::length(got[i] - want[i]), 2e-6) << "vertex " << i;
    EXPECT_EQ(d.root()["animations"][0]["samplers"][0]["interpolation"], "LINEAR");
}

TEST(MorphGlb, missingFrameOrWrongVertexCountLeavesNoFile) {
    const std::string dir = test::scratchDir("morph_glb_errors");
    const Polylines c = test::mixedCurves();
    MorphTopology base;
    base.positions = c.points;
    base.indices = segmentIndices(c.offsets, c.closed);
    {
        MorphGlbWriter w(dir + "/a.glb", base, 3, {});
        w.writeFrame(c.points);
        EXPECT_THROW(w.writeFrame(std::vector<glm::dvec3>(5)), Error);
        EXPECT_THROW(w.commit(), Error);  // 1 of 3 frames
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir));
    EXPECT_THROW(MorphGlbWriter(dir + "/a.gltf", base, 3, {}), Error);
    EXPECT_THROW(MorphGlbWriter(dir + "/a.glb", base, 0, {}), Error);
}

TEST(MorphGlb, sizeEstimateGrowsWithFramesTimesVertices) {
    const double one = morphGlbBytes(1000, 2000, 10, false), more = morphGlbBytes(1000, 2000, 20, false);
    EXPECT_GE(more - one, 10 * 1000 * 12.0);
    EXPECT_GT(morphGlbBytes(1000, 2000, 10, true), one);
}

}  // namespace
}  // namespace knit
