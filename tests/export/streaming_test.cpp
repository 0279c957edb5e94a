// Streaming export: chunks bound the tube mesh held in memory (VmHWM growth during the export
// stays near one chunk, far below the whole mesh), and chunking does not change the geometry.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "export/gltf_read.hpp"
#include "export/test_curves.hpp"
#include "knit/export.hpp"
#include "knit/sweep.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

// Resets VmHWM to the current resident size (Linux >= 4.0); false if unsupported.
bool resetPeak() {
    return util::resetPeakResident() && util::peakResidentBytes() <= util::residentBytes() + (1u << 20);
}

TEST(Streaming, peakMemoryGrowsByAboutOneChunkNotTheWholeMesh) {
    const std::string dir = test::scratchDir("streaming");
    // ~1.3M tube vertices (about 100 MB as one mesh); chunks of 32k vertices (about 2.5 MB).
    const Polylines c = test::planeRows(240, 600, 0.0005, glm::dvec3(10, 0, 0), 0.0004);
    ExportInput in;
    in.curves = &c;
    in.radius = 0.0002;
    ExportOptions o;
    o.path = dir + "/big.glb";
    o.what = ExportWhat::Tubes;
    o.chunkVertices = 32768;
    if (!resetPeak()) GTEST_SKIP() << "kernel cannot reset VmHWM";
    const size_t before = util::residentBytes();
    const ExportStats s = exportCurves(in, o);
    const double whole = double(s.vertices) * 52.0 + double(s.triangles) * 12.0;
    ASSERT_GT(whole, 80e6);
    EXPECT_LE(s.maxChunkVertices, o.chunkVertices);
    EXPECT_GE(s.chunks, 40u);
    EXPECT_LE(s.peakMemoryBytes, util::peakResidentBytes());
    const double growth = double(s.peakMemoryBytes) - double(before);
    // Non-streaming would need >= 1.0 x whole; one chunk plus writer buffers is ~0.05 x here
    // (0.3 leaves room for sanitizer builds' allocator overhead).
    EXPECT_LT(growth, 0.3 * whole) << "peak grew by " << growth / 1e6 << " MB for a " << whole / 1e6
                                   << " MB mesh: not streaming";
    std::filesystem::remove(o.path);
}

TEST(Streaming, chunkSizeDoesNotChangeTheGeometry) {
    const std::string dir = test::scratchDir("streaming_same");
    const Polylines c = test::mixedCurves(glm::dvec3(2, 3, 4));
    ExportInput in;
    in.curves = &c;
    in.radius = 0.001;
    ExportOptions a;
    a.path = dir + "/one.obj";
    a.what = ExportWhat::Tubes;
    ExportOptions b = a;
    b.path = dir + "/many.obj";
    b.chunkVertices = 100;  // below one curve: one chunk per curve
    EXPECT_EQ(exportCurves(in, a).chunks, 1u);
    EXPECT_EQ(exportCurves(in, b).chunks, 3u);
    // OBJ holds world coordinates (chunks write their v / vn / vt / f blocks one after the other):
    // per record type the sequences agree, positions up to float32 rounding at each chunk origin.
    auto records = [](const std::string& text) {
        std::map<std::string, std::vector<std::string>> r;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            const std::string tag = line.substr(0, line.find(' '));
            if (tag != "#") r[tag].push_back(line.substr(tag.size()));
        }
        return r;
    };
    auto ra = records(test::readText(a.path)), rb = records(test::readText(b.path));
    EXPECT_EQ(ra["vn"], rb["vn"]);
    EXPECT_EQ(ra["vt"], rb["vt"]);
    EXPECT_EQ(ra["f"], rb["f"]);
    ASSERT_EQ(ra["v"].size(), rb["v"].size());
    size_t vertices = 0;
    for (size_t i = 0; i < ra["v"].size(); ++i) {
        std::istringstream pa(ra["v"][i]), pb(rb["v"][i]);
        glm::dvec3 p, q;
        pa >> p.x >> p.y >> p.z;
        pb >> q.x >> q.y >> q.z;
        EXPECT_LT(glm::length(p - q), 1e-6);
        ++vertices;
    }
    EXPECT_EQ(vertices, (42 + 33 + 27) * 9u);
}

}  // namespace
}  // namespace knit
