// PointCacheWriter: PC2 / MDD headers and byte order read back by an independent reader, the
// segment OBJ topology, and no partial cache after an error.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "knit/cache.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

// Independent reader: explicit byte order, no shared code with the writer.
uint32_t readU32(const std::vector<unsigned char>& b, size_t at, bool bigEndian) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(b[at + i]) << (bigEndian ? 24 - 8 * i : 8 * i);
    return v;
}
float readF32(const std::vector<unsigned char>& b, size_t at, bool bigEndian) {
    const uint32_t v = readU32(b, at, bigEndian);
    float f;
    static_assert(sizeof f == 4);
    __builtin_memcpy(&f, &v, 4);
    return f;
}

std::vector<glm::dvec3> framePoints(int k) { return {{1.5 + k, -2.0, 0.25}, {0.0, 3.0 * k, -1.0}, {k, k, k}}; }

void writeCache(const std::string& path, int frames) {
    CacheInfo info;
    info.points = 3;
    info.frames = frames;
    info.startFrame = 7;
    info.fps = 25;
    PointCacheWriter w(path, info);
    for (int k = 0; k < frames; ++k) w.writeFrame(framePoints(k));
    w.commit();
}

TEST(PointCache, pc2HeaderAndLittleEndianFramesPerSpecification) {
    const test::TempDir dir;
    writeCache(dir.file("a.pc2"), 2);
    const std::vector<unsigned char> b = test::readBytes(dir.file("a.pc2"));
    ASSERT_EQ(b.size(), 32u + 2 * 3 * 12);
    EXPECT_EQ(std::string(b.begin(), b.begin() + 12), std::string("POINTCACHE2\0", 12));
    EXPECT_EQ(readU32(b, 12, false), 1u);    // version
    EXPECT_EQ(readU32(b, 16, false), 3u);    // points
    EXPECT_EQ(readF32(b, 20, false), 7.0f);  // start frame
    EXPECT_EQ(readF32(b, 24, false), 1.0f);  // sample rate
    EXPECT_EQ(readU32(b, 28, false), 2u);    // samples
    for (int k = 0; k < 2; ++k)
        for (int p = 0; p < 3; ++p)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(readF32(b, 32 + (k * 3 + p) * 12 + c * 4, false), float(framePoints(k)[p][c]));
}

TEST(PointCache, mddHeaderTimesAndBigEndianFramesPerSpecification) {
    const test::TempDir dir;
    writeCache(dir.file("a.mdd"), 3);
    const std::vector<unsigned char> b = test::readBytes(dir.file("a.mdd"));
    ASSERT_EQ(b.size(), 8u + 3 * 4 + 3 * 3 * 12);
    EXPECT_EQ(readU32(b, 0, true), 3u);  // frames
    EXPECT_EQ(readU32(b, 4, true), 3u);  // points
    for (int k = 0; k < 3; ++k) EXPECT_EQ(readF32(b, 8 + 4 * k, true), float(k / 25.0));
    for (int k = 0; k < 3; ++k)
        for (int p = 0; p < 3; ++p)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(readF32(b, 20 + (k * 3 + p) * 12 + c * 4, true), float(framePoints(k)[p][c]));
}

TEST(PointCache, missingFramesOrWrongCountsLeaveNoCacheAndNoTempFile) {
    const test::TempDir dir;
    std::string temp;
    {
        CacheInfo info;
        info.points = 3;
        info.frames = 2;
        PointCacheWriter w(dir.file("a.pc2"), info);
        temp = w.tempPath();
        EXPECT_TRUE(std::filesystem::exists(temp));
        w.writeFrame(framePoints(0));
        EXPECT_EQ(test::errorOf([&] {
                      w.writeFrame({{0, 0, 0}});
                  }),
                  "point cache '" + dir.file("a.pc2") + "': frame 1 has 1 points, the cache 3");
        EXPECT_EQ(test::errorOf([&] { w.commit(); }), "point cache '" + dir.file("a.pc2") + "': 1 of 2 frames written");
    }
    EXPECT_FALSE(std::filesystem::exists(temp));
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.pc2")));
}

TEST(PointCache, segmentObjHasOneLineRecordPerSegmentAndClosesLoops) {
    const test::TempDir dir;
    Polylines c;
    const glm::dvec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    c.addCurve(p, 3, false);
    c.addCurve(p, 4, true);
    writeSegmentObj(dir.file("t.obj"), c, "test");
    const std::string text = test::readText(dir.file("t.obj"));
    EXPECT_NE(text.find("l 1 2\nl 2 3\nl 4 5\nl 5 6\nl 6 7\nl 7 4\n"), std::string::npos) << text;
    EXPECT_EQ(text.find("l 3 4"), std::string::npos);
}

TEST(PointCache, unknownExtensionIsRefused) {
    const test::TempDir dir;
    EXPECT_EQ(test::errorOf([&] { PointCacheWriter(dir.file("a.abc"), CacheInfo{}); }),
              "cannot write point cache '" + dir.file("a.abc") + "': the extension must be .pc2 or .mdd");
}

}  // namespace
}  // namespace knit
