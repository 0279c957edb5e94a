// The export part of `knit build --report` (apps/knit/export_report.cpp).
#include <gtest/gtest.h>

#include "export_report.hpp"
#include "util/platform.hpp"

namespace knit::cli {
namespace {

TEST(ExportReport, carriesCountsPeakMemoryAndRatio) {
    ExportStats s;
    s.format = "glb";
    s.vertices = 10;
    s.uncompressedMeshBytes = 1000;
    s.compressedMeshBytes = 250;
    s.peakMemoryBytes = util::peakResidentBytes();
    EXPECT_GT(s.peakMemoryBytes, 0u);
    const nlohmann::json j = exportReport(s);
    EXPECT_EQ(j["format"], "glb");
    EXPECT_EQ(j["vertices"], 10);
    EXPECT_DOUBLE_EQ(j["compressionRatio"].get<double>(), 4.0);
    EXPECT_EQ(j["peakMemoryBytes"].get<size_t>(), s.peakMemoryBytes);
}

TEST(ExportReport, curvesHaveNoMeshBytesOrRatio) {
    ExportStats s;
    s.format = "obj";
    s.curves = 3;
    const nlohmann::json j = exportReport(s);
    EXPECT_EQ(j["curves"], 3);
    EXPECT_FALSE(j.contains("uncompressedMeshBytes"));
    EXPECT_FALSE(j.contains("compressedMeshBytes"));
    EXPECT_FALSE(j.contains("compressionRatio"));
}

}  // namespace
}  // namespace knit::cli
