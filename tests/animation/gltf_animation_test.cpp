// glTF animation input (knit::GltfAnimation, FrameSequence over one animated glTF) on the small
// files of common/animated_gltf.hpp: a quad with a morph target whose weight goes 0 -> 1, and the
// same quad skinned to one joint that turns 90 degrees about z.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "common/animated_gltf.hpp"
#include "test_util.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

using test::GltfText;
using test::kQuad;
using test::quadPrimitive;
using test::writeMorphQuad;
using test::writeSkinnedQuad;

std::string scratch(const std::string& name) {
    const std::string dir = (std::filesystem::temp_directory_path() / ("knit_gltf_anim_" + name)).string();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

glm::dvec3 quadVertex(size_t i) { return {kQuad[3 * i], kQuad[3 * i + 1], kQuad[3 * i + 2]}; }

TEST(GltfAnimation, morphWeightGivesBasePlusWeightTimesDelta) {
    const std::string path = writeMorphQuad(scratch("morph"));
    const GltfAnimation keys(path);  // keyframes 0 and 1 s
    ASSERT_EQ(keys.times(), (std::vector<double>{0.0, 1.0}));
    const GltfAnimation a(path, 4.0);  // 0, 0.25, ..., 1 s
    ASSERT_EQ(a.times().size(), 5u);
    for (size_t s = 0; s < a.times().size(); ++s) {
        const BaseMesh m = a.sample(s);
        ASSERT_EQ(m.positions.size(), 4u);
        const double w = a.times()[s];  // the weight rises linearly 0 -> 1 over 1 s
        for (size_t i = 0; i < 4; ++i)
            EXPECT_NEAR(glm::length(m.positions[i] - (quadVertex(i) + w * glm::dvec3(0, 0, double(i + 1)))), 0.0, 1e-12)
                << "sample " << s << " vertex " << i;
    }
}

TEST(GltfAnimation, skinnedJointRotationTurnsTheMesh) {
    const std::string path = writeSkinnedQuad(scratch("skin"));
    const GltfAnimation a(path, 2.0);  // 0, 45, 90 degrees
    ASSERT_EQ(a.times().size(), 3u);
    for (size_t s = 0; s < 3; ++s) {
        const BaseMesh m = a.sample(s);
        const double angle = 0.25 * knit::util::kPi * double(s), c = std::cos(angle), sn = std::sin(angle);
        for (size_t i = 0; i < 4; ++i) {
            const glm::dvec3 p = quadVertex(i), want(c * p.x - sn * p.y, sn * p.x + c * p.y, p.z);
            EXPECT_NEAR(glm::length(m.positions[i] - want), 0.0, 1e-6) << "sample " << s << " vertex " << i;
        }
    }
}

// Joint indices stored as signed bytes (-64): the spec allows only unsigned types, and the old
// reader turned -64 into a size_t (the fuzzer's UBSan finding in CI, stop 32).
TEST(GltfAnimation, signedJointIndicesAreRefusedNamingTheAttribute) {
    const std::string path = writeSkinnedQuad(scratch("signed_joints"), /*signedJoints=*/true);
    const std::string e = test::errorOf([&] { GltfAnimation(path, 2.0).sample(1); });
    EXPECT_NE(e.find("JOINTS_0 must hold unsigned bytes or unsigned shorts (componentType 5121 or 5123), not "
                     "componentType 5120"),
              std::string::npos)
        << e;
}

TEST(GltfAnimation, frameSequenceOverOneAnimatedFileKeepsRestConnectivityAndUvs) {
    const std::string path = writeMorphQuad(scratch("sequence"));
    FrameRange range;
    range.fps = 4;
    const FrameSequence seq(path, range);
    ASSERT_EQ(seq.size(), 5u);
    EXPECT_EQ(seq.frame(4).number, 5);
    const BaseMesh rest = loadMesh(path);  // the un-animated mesh
    const BaseMesh last = seq.load(4, rest);
    EXPECT_EQ(last.uvs, rest.uvs);
    EXPECT_NEAR(last.positions[3].z, 4.0, 1e-12);
    range.last = 9;
    EXPECT_NE(test::errorOf([&] { FrameSequence(path, range); }).find("frame 6 is missing"), std::string::npos);
}

TEST(GltfAnimation, fileWithoutAnimationIsRefusedNamingIt) {
    const std::string dir = scratch("none");
    GltfText g;
    g.j["meshes"] = {{{"primitives", {quadPrimitive(g)}}}};
    g.j["nodes"] = {{{"mesh", 0}}};
    g.j["scenes"] = {{{"nodes", {0}}}};
    test::writeText(dir + "/still.gltf", g.text());
    const std::string e = test::errorOf([&] { GltfAnimation(dir + "/still.gltf"); });
    EXPECT_NE(e.find("still.gltf"), std::string::npos) << e;
    EXPECT_NE(e.find("has no animation 0"), std::string::npos) << e;
}

// A still quad whose node has one animation channel (`path`) of the given key times and output.
std::string writeOneChannelQuad(const std::string& file, const std::vector<float>& times,
                                const std::vector<float>& output, const char* type, size_t outputCount,
                                const char* path) {
    GltfText g;
    nlohmann::json prim = quadPrimitive(g);
    g.j["meshes"] = {{{"primitives", {prim}}}};
    g.j["nodes"] = {{{"mesh", 0}}};
    g.j["scenes"] = {{{"nodes", {0}}}};
    const int in = g.add(times, 5126, "SCALAR", times.size());
    const int out = g.add(output, 5126, type, outputCount);
    nlohmann::json anim;
    anim["samplers"] = nlohmann::json::array({{{"input", in}, {"output", out}}});
    anim["channels"] = nlohmann::json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}}});
    g.j["animations"] = nlohmann::json::array({anim});
    test::writeText(file, g.text());
    return file;
}

// A rotation keyed twice with one quaternion in its output: 4 numbers for 2 keys would pass as
// 2 numbers per key; the path's width (4) refuses it before any sample reads past the values
// (the fuzzer's heap overflow, tests/fuzz_corpus/gltf_animation/rotation_output_too_short.gltf).
TEST(GltfAnimation, channelOutputsOfTheWrongWidthForTheirPathAreRefused) {
    const std::string path =
        writeOneChannelQuad(scratch("width") + "/bad.gltf", {0, 1}, {0, 0, 0, 1}, "VEC4", 1, "rotation");
    const std::string e = test::errorOf([&] { GltfAnimation(path, 0).sample(1); });
    EXPECT_NE(e.find("animations[0].channels[0]: a rotation channel needs 4 numbers per key, but its sampler's "
                     "output has 2 per key"),
              std::string::npos)
        << e;
}

TEST(GltfAnimation, keyTimesThatDoNotIncreaseAreRefusedNamingTheChannel) {
    // A translation keyed twice at 1 s.
    const std::string path =
        writeOneChannelQuad(scratch("times") + "/bad.gltf", {1, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", 2, "translation");
    const std::string e = test::errorOf([&] { GltfAnimation(path, 0); });
    EXPECT_NE(e.find("animations[0].channels[0]: the sampler's input time 1 is not finite or not after the previous"),
              std::string::npos)
        << e;
    EXPECT_NE(test::errorOf([&] { GltfAnimation(writeMorphQuad(scratch("fps")), 1e9); }).find("more than 1e6 frames"),
              std::string::npos);
}

}  // namespace
}  // namespace knit
