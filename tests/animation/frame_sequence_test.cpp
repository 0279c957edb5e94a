// FrameSequence: printf patterns and numbered folders, ranges, and bad sequences refused with
// the frame named (missing frame, changed vertex count, NaN in frame 37, non-matching UVs).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

// A unit square of two triangles with UVs, lifted by z; `extraVertex` adds a vertex (and a
// triangle using it), `uvShift` moves UV 2, `nanZ` makes vertex 1 not finite.
std::string squareObj(double z, bool extraVertex = false, double uvShift = 0.0, bool nanZ = false) {
    const std::string zs = std::to_string(z);
    std::string s =
        "v 0 0 " + zs + "\nv 1 0 " + (nanZ ? std::string("nan") : zs) + "\nv 1 1 " + zs + "\nv 0 1 " + zs + "\n";
    s += "vt 0 0\nvt 1 0\nvt " + std::to_string(1 + uvShift) + " 1\nvt 0 1\n";
    s += "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    if (extraVertex) s += "v 2 2 " + zs + "\nf 2/2 5/3 3/3\n";
    return s;
}

std::string frameName(int k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%04d.obj", k);
    return buf;
}

void writeFrames(const test::TempDir& dir, int first, int last) {
    for (int k = first; k <= last; ++k) dir.write(frameName(k), squareObj(0.01 * k));
}

TEST(FrameSequence, printfPatternFindsItsRangeFromTheFiles) {
    const test::TempDir dir;
    writeFrames(dir, 1, 5);
    const FrameSequence seq(dir.file("frame_%04d.obj"));
    ASSERT_EQ(seq.size(), 5u);
    EXPECT_EQ(seq.frame(0).number, 1);
    EXPECT_EQ(seq.frame(4).path, dir.file("frame_0005.obj"));
}

TEST(FrameSequence, folderOfNumberedFilesWithFirstLastAndStep) {
    const test::TempDir dir;
    writeFrames(dir, 1, 9);
    FrameRange r;
    r.first = 2;
    r.last = 8;
    r.step = 3;
    const FrameSequence seq(dir.path().string(), r);
    ASSERT_EQ(seq.size(), 3u);
    EXPECT_EQ(seq.frame(0).number, 2);
    EXPECT_EQ(seq.frame(1).number, 5);
    EXPECT_EQ(seq.frame(2).number, 8);
}

TEST(FrameSequence, missingFrameIsNamed) {
    const test::TempDir dir;
    writeFrames(dir, 1, 5);
    std::remove(dir.file("frame_0003.obj").c_str());
    EXPECT_EQ(test::errorOf([&] { FrameSequence(dir.file("frame_%04d.obj")); }),
              "frame 3 is missing: '" + dir.file("frame_0003.obj") + "' does not exist");
    EXPECT_EQ(test::errorOf([&] { FrameSequence(dir.path().string()); }),
              "frame 3 is missing: no mesh file numbered 3 in folder '" + dir.path().string() + "'");
}

TEST(FrameSequence, changedVertexCountIsNamedWithTheFrame) {
    const test::TempDir dir;
    writeFrames(dir, 1, 3);
    dir.write(frameName(2), squareObj(0.02, true));
    const FrameSequence seq(dir.file("frame_%04d.obj"));
    const BaseMesh rest = seq.load(0, loadMesh(seq.frame(0).path));
    EXPECT_EQ(test::errorOf([&] { seq.load(1, rest); }),
              "frame 2 ('" + dir.file("frame_0002.obj") +
                  "'): has 5 vertices but the rest mesh 4 (a sequence must keep the rest mesh's connectivity and UVs)");
}

TEST(FrameSequence, nanInFrame37IsNamed) {
    const test::TempDir dir;
    writeFrames(dir, 1, 40);
    dir.write(frameName(37), squareObj(0.37, false, 0.0, true));
    const FrameSequence seq(dir.file("frame_%04d.obj"));
    const BaseMesh rest = loadMesh(seq.frame(0).path);
    for (size_t i = 0; i < 36; ++i) seq.load(i, rest);
    const std::string e = test::errorOf([&] { seq.load(36, rest); });
    EXPECT_EQ(e.rfind("frame 37 ('" + dir.file("frame_0037.obj") + "'): ", 0), 0u) << e;
}

TEST(FrameSequence, nonMatchingUvsAreNamed) {
    const test::TempDir dir;
    writeFrames(dir, 1, 2);
    dir.write(frameName(2), squareObj(0.02, false, 0.5));
    const FrameSequence seq(dir.file("frame_%04d.obj"));
    const BaseMesh rest = loadMesh(seq.frame(0).path);
    const std::string e = test::errorOf([&] { seq.load(1, rest); });
    EXPECT_EQ(e.rfind("frame 2 ('" + dir.file("frame_0002.obj") + "'): UV 2 is (1.500000, 1.000000)", 0), 0u) << e;
}

TEST(FrameSequence, patternWithoutConversionIsRefused) {
    EXPECT_EQ(
        test::errorOf([] { FrameSequence("frames.obj"); }),
        "the frame sequence: 'frames.obj' is neither a folder nor a file pattern with one integer conversion (e.g. "
        "frame_%04d.obj)");
}

}  // namespace
}  // namespace knit
