// OBJ polylines and tube meshes, atomic writing.
#include <gtest/gtest.h>

#include <sstream>

#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "obj_writer.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

struct ObjData {
    std::vector<glm::dvec3> v;
    std::vector<std::vector<long>> lines;  // `l` records (1-based)
    std::vector<std::vector<long>> faces;  // `f` records (vertex index only)
    size_t vn = 0, vt = 0;
};

// A minimal independent OBJ reader for what the writer emits.
ObjData parseObj(const std::string& text) {
    ObjData d;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string tag;
        ls >> tag;
        if (tag == "v") {
            glm::dvec3 p;
            ls >> p.x >> p.y >> p.z;
            d.v.push_back(p);
        } else if (tag == "vn") {
            ++d.vn;
        } else if (tag == "vt") {
            ++d.vt;
        } else if (tag == "l" || tag == "f") {
            std::vector<long> idx;
            std::string tok;
            while (ls >> tok) idx.push_back(std::stol(tok.substr(0, tok.find('/'))));
            (tag == "l" ? d.lines : d.faces).push_back(idx);
        }
    }
    return d;
}

TEST(ObjExport, polylinesAreTwoIndexSegmentsAndLoopsEndWithTheClosingSegment) {
    Polylines c;
    const glm::dvec3 open[3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    const glm::dvec3 loop[4] = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    c.addCurve(open, 3, false);
    c.addCurve(loop, 4, true);
    std::ostringstream out;
    impl::writeObjPolylines(out, c, "two curves\nsecond line");
    const ObjData d = parseObj(out.str());
    ASSERT_EQ(d.v.size(), 7u);
    // Every segment its own `l i j` record (Blender 3.4 keeps only the first segment of longer ones).
    const std::vector<std::vector<long>> segments = {{1, 2}, {2, 3}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
    EXPECT_EQ(d.lines, segments);
    EXPECT_NE(out.str().find("# second line\n"), std::string::npos);
}

TEST(ObjExport, polylineCoordinatesRoundTripExactly) {
    Polylines c;
    const glm::dvec3 p[2] = {{0.1, 1.0 / 3.0, -123456.789012345678}, {1e-17, 6.02214076e23, util::kPi}};
    c.addCurve(p, 2, false);
    std::ostringstream out;
    impl::writeObjPolylines(out, c, "");
    const ObjData d = parseObj(out.str());
    ASSERT_EQ(d.v.size(), 2u);
    for (int i = 0; i < 2; ++i) EXPECT_EQ(d.v[i], p[i]) << "vertex " << i;
}

TEST(ObjExport, singlePointCurveWritesNoLineRecord) {
    Polylines c;
    const glm::dvec3 one(1, 2, 3);
    const glm::dvec3 two[2] = {{0, 0, 0}, {1, 0, 0}};
    c.addCurve(&one, 1, false);
    c.addCurve(two, 2, false);
    std::ostringstream out;
    impl::writeObjPolylines(out, c, "");
    const ObjData d = parseObj(out.str());
    ASSERT_EQ(d.lines.size(), 1u);
    EXPECT_EQ(d.lines[0], (std::vector<long>{2, 3}));
}

TEST(ObjExport, tubeMeshIndicesContinueAcrossChunks) {
    const std::string dir = test::scratchDir("obj_tubes");
    const Polylines c = test::mixedCurves();
    ExportInput in;
    in.curves = &c;
    in.radius = 0.001;
    ExportOptions o;
    o.what = ExportWhat::Tubes;
    o.sides = 6;
    o.chunkVertices = 200;  // forces one chunk per curve
    o.path = dir + "/tubes.obj";
    const ExportStats s = exportCurves(in, o);
    EXPECT_EQ(s.chunks, 3u);
    const ObjData d = parseObj(test::readText(o.path));
    // open: n rings + 2 caps of 7; closed: n + 1 rings; 7 vertices per ring (6 + seam).
    const size_t expected = (40 + 2) * 7 + (32 + 1) * 7 + (25 + 2) * 7;
    ASSERT_EQ(d.v.size(), expected);
    EXPECT_EQ(d.vn, expected);
    EXPECT_EQ(d.vt, expected);
    EXPECT_EQ(s.vertices, expected);
    const size_t tris = 39 * 12 + 6 * 2 + 32 * 12 + 24 * 12 + 6 * 2;
    ASSERT_EQ(d.faces.size(), tris);
    long maxIndex = 0;
    for (const auto& f : d.faces) {
        ASSERT_EQ(f.size(), 3u);
        for (long i : f) {
            EXPECT_GE(i, 1);
            maxIndex = std::max(maxIndex, i);
        }
    }
    EXPECT_EQ(maxIndex, long(expected));
    // Every tube vertex lies one radius from its curve (ring) or on it (cap centre).
    for (const glm::dvec3& v : d.v) {
        double best = 1e9;
        for (const glm::dvec3& p : c.points) best = std::min(best, glm::length(v - p));
        EXPECT_LE(best, 0.001 * (1 + 1e-5));
    }
}

TEST(AtomicWrite, callbackExceptionLeavesNoFile) {
    const std::string dir = test::scratchDir("atomic_throw");
    const std::string path = dir + "/out.obj";
    EXPECT_THROW(writeFileAtomically(
                     path,
                     [](std::ostream& out) {
                         out << "partial data";
                         throw std::runtime_error("writer failed half way");
                     },
                     false),
                 std::runtime_error);
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(AtomicWrite, missingFolderIsNamedInError) {
    const std::string dir = test::scratchDir("atomic_missing");
    const std::string path = dir + "/no/such/folder/out.obj";
    try {
        writeFileAtomically(
            path, [](std::ostream& out) { out << "x"; }, false);
        FAIL() << "expected knit::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(test::listDir(dir).empty());
}

TEST(AtomicWrite, replacesExistingFileOnlyOnSuccess) {
    const std::string dir = test::scratchDir("atomic_replace");
    const std::string path = dir + "/out.txt";
    writeFileAtomically(
        path, [](std::ostream& out) { out << "first"; }, false);
    EXPECT_EQ(test::readText(path), "first");
    EXPECT_THROW(writeFileAtomically(
                     path, [](std::ostream&) { throw Error("fail"); }, false),
                 Error);
    EXPECT_EQ(test::readText(path), "first");
    writeFileAtomically(
        path, [](std::ostream& out) { out << "second"; }, false);
    EXPECT_EQ(test::readText(path), "second");
    EXPECT_EQ(test::listDir(dir).size(), 1u);
}

}  // namespace
}  // namespace knit
