// Bound scene files (knit/bound_scene.hpp): a loaded scene evaluates frames to the same bytes as
// the scene that was saved; other versions and damaged files are refused saying which.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include <boost/crc.hpp>

#include "knit/animation.hpp"
#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

Scene restScene() {
    SceneOptions o;
    o.pattern = "stockinette";
    o.mesh = "drape";
    o.meshOptions.resU = o.meshOptions.resV = 8;
    o.placement.repeats = {4, 4};
    o.buildPlies = false;
    o.plies.count = 3;
    return buildScene(o);
}

// The rest positions moved by a wave (a frame of the same connectivity).
std::vector<glm::dvec3> waved(const BaseMesh& m) {
    std::vector<glm::dvec3> p = m.positions;
    for (glm::dvec3& x : p) x.z += 0.01 * std::sin(40 * x.x) + 0.003 * x.y;
    return p;
}

std::string errorOf(const std::string& bytes) {
    try {
        decodeBoundScene(bytes, "g.knitbind");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// `bytes` with the header's checksum recomputed over its (edited) payload.
std::string resealed(std::string bytes) {
    boost::crc_32_type crc;
    crc.process_bytes(bytes.data() + 32, bytes.size() - 32);
    const uint32_t c = crc.checksum();
    std::memcpy(bytes.data() + 24, &c, 4);
    return bytes;
}

TEST(BoundScene, loadedSceneEvaluatesFramesToTheSameBytes) {
    const Scene rest = restScene();
    BoundSceneInfo info;
    info.settings = R"({"writer":"test"})";
    info.strainTable = "tables/wool.strain";
    const std::string bytes = encodeBoundScene(rest, info);
    const BoundScene loaded = decodeBoundScene(bytes, "g.knitbind");
    EXPECT_EQ(loaded.info.settings, info.settings);
    EXPECT_EQ(loaded.info.strainTable, info.strainTable);
    EXPECT_EQ(loaded.scene.pattern().name, rest.pattern().name);
    EXPECT_EQ(loaded.scene.yarnRadius(), rest.yarnRadius());
    EXPECT_EQ(loaded.scene.yarnMargin(), rest.yarnMargin());
    EXPECT_EQ(loaded.scene.bindStats().openEnds, rest.bindStats().openEnds);
    EXPECT_EQ(loaded.scene.grid().cells, rest.grid().cells);
    ASSERT_EQ(loaded.scene.yarns().curves.points, rest.yarns().curves.points);
    // The same frame through an Animator of each: the plies bit for bit.
    const Animator a(rest), b(loaded.scene);
    AnimationFrame fa, fb;
    const std::vector<glm::dvec3> frame = waved(rest.mesh());
    a.evaluate(frame, fa);
    b.evaluate(frame, fb);
    ASSERT_GT(fa.plies.curves.pointCount(), 1000u);
    EXPECT_EQ(fa.plies.curves.points, fb.plies.curves.points);
    EXPECT_EQ(fa.plies.curves.offsets, fb.plies.curves.offsets);
    EXPECT_EQ(fa.stats.maxStretch, fb.stats.maxStretch);
    // And the file round-trips to the same bytes.
    EXPECT_EQ(encodeBoundScene(loaded.scene, loaded.info), bytes);
}

TEST(BoundScene, otherVersionsAndDamagedFilesAreRefusedSayingWhich) {
    const std::string bytes = encodeBoundScene(restScene(), {});
    std::string v = bytes;
    v[8] = 7;  // format version 7
    EXPECT_NE(errorOf(v).find("has format version 7; this knit reads version 1"), std::string::npos) << errorOf(v);
    EXPECT_NE(errorOf(bytes.substr(0, bytes.size() - 100)).find("is truncated"), std::string::npos);
    EXPECT_NE(errorOf(bytes.substr(0, 20)).find("is truncated"), std::string::npos);
    EXPECT_NE(errorOf(bytes + "x").find("is damaged: 1 bytes follow"), std::string::npos);
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    EXPECT_NE(errorOf(flipped).find("is damaged: its checksum does not match"), std::string::npos);
    EXPECT_NE(errorOf("PK\3\4 a zip file").find("is not a bound scene file"), std::string::npos);
    // A count beyond the file (checksum valid): refused before allocating.
    std::string huge = bytes;
    const uint64_t n = uint64_t(1) << 60;
    std::memcpy(huge.data() + 32, &n, 8);  // the settings' length
    EXPECT_NE(errorOf(resealed(huge)).find("is damaged: the settings claim"), std::string::npos);
}

TEST(BoundScene, aSceneMadeFromPartsIsNotSaved) {
    SceneParts parts;
    parts.yarnRadius = 0.001;
    EXPECT_THROW(encodeBoundScene(Scene::fromParts(parts), {}), Error);
}

}  // namespace
}  // namespace knit
