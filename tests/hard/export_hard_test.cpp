// Hard cases for the exporters: unwritable outputs in every format (knit::Error naming the path,
// no output file, no temporary file left behind), scenes with nothing to export (refused), and a scene far
// from the origin written as text curves (no precision lost).
#ifdef KNIT_HARD_HAVE_EXPORTERS
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "catalogue.hpp"
#include "knit/export.hpp"
#include "test_util.hpp"

namespace knit::hard {
namespace {

namespace fs = std::filesystem;

class ExportHard : public ::testing::Test {
protected:
    size_t fileCount() const {
        size_t n = 0;
        for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
        return n;
    }
    test::TempDir tmp;
    const fs::path dir = tmp.path();
};

const char* kExtensions[] = {".obj", ".ply", ".bcc", ".pbrt", ".gltf", ".glb"};

Scene smallScene() { return buildScene(generateStockinette(), flatSquare(4, 0.02), withRepeats(3, 3)); }

TEST_F(ExportHard, unwritablePathsThrowNamingThePathAndLeaveNothing) {
    std::ofstream(dir / "afile") << "x";
    fs::create_directories(dir / "adir");
    // With plies built, and without (plies generated while writing: streamed into glTF).
    for (const Scene& scene :
         {smallScene(), buildScene(generateStockinette(), flatSquare(4, 0.02), withRepeats(3, 3, false))}) {
        for (const char* ext : kExtensions)
            for (const ExportWhat what : {ExportWhat::Yarns, ExportWhat::Plies, ExportWhat::Tubes}) {
                for (const fs::path& target : {dir / "no" / "such" / (std::string("out") + ext),
                                               dir / "afile" / (std::string("out") + ext), dir / "adir"}) {
                    ExportOptions o;
                    o.path = target.string();
                    o.what = what;
                    const size_t before = fileCount();
                    try {
                        exportScene(scene, o);
                        ADD_FAILURE() << "exported to " << o.path;
                    } catch (const Error& e) {
                        EXPECT_NE(std::string(e.what()).find(o.path), std::string::npos) << e.what();
                    } catch (const std::exception& e) {
                        ADD_FAILURE() << o.path << ": non-knit exception " << e.what();
                    }
                    EXPECT_EQ(fileCount(), before) << o.path;
                    EXPECT_TRUE(fs::is_directory(dir / "adir"));
                }
            }
    }
}

TEST_F(ExportHard, sceneWithNothingToExportIsRefusedAndLeavesNoFile) {
    // A UV island smaller than a stitch: no yarn survives (with plies built, and without).
    for (const bool plies : {true, false}) {
        const Scene scene = buildScene(generateStockinette(), flatSquare(2, 1e-4), withRepeats(0.01, 0.01, plies));
        ASSERT_EQ(scene.yarns().curves.pointCount(), 0u);
        for (const char* ext : kExtensions)
            for (const ExportWhat what : {ExportWhat::Yarns, ExportWhat::Plies, ExportWhat::Tubes}) {
                ExportOptions o;
                o.path = (dir / (std::string("empty") + ext)).string();
                o.what = what;
                try {
                    exportScene(scene, o);
                    ADD_FAILURE() << "exported " << o.path;
                } catch (const Error& e) {
                    EXPECT_FALSE(fs::exists(o.path)) << e.what();
                } catch (const std::exception& e) {
                    ADD_FAILURE() << o.path << ": non-knit exception " << e.what();
                }
                EXPECT_EQ(fileCount(), 0u) << o.path;
            }
    }
}

// A failure in the middle of a streamed export (here: a generated chunk larger than the buffer
// limit, known only once it is generated) stops the pipeline with knit::Error and leaves no file.
TEST_F(ExportHard, failureInsideTheStreamedPipelineLeavesNoFile) {
    const Scene scene = buildScene(generateStockinette(), flatSquare(4, 0.02), withRepeats(6, 6, false));
    for (const char* ext : {".glb", ".gltf"}) {
        ExportOptions o;
        o.path = (dir / (std::string("big") + ext)).string();
        o.what = ExportWhat::Plies;
        o.maxBufferBytes = 4096;  // smaller than one chunk
        try {
            exportScene(scene, o);
            ADD_FAILURE() << "exported " << o.path;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("the vertices per chunk"), std::string::npos) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << o.path << ": non-knit exception " << e.what();
        }
        EXPECT_EQ(fileCount(), 0u) << o.path;
    }
}

TEST_F(ExportHard, farFromOriginObjCurvesKeepDoublePrecision) {
    BaseMesh m = flatSquare(4, 0.02);
    const glm::dvec3 shift(1e5, -1e5, 3e4);
    for (glm::dvec3& p : m.positions) p += shift;
    const Scene scene = buildScene(generateStockinette(), m, withRepeats(3, 3, false));
    ExportOptions o;
    o.path = (dir / "far.obj").string();
    o.what = ExportWhat::Yarns;
    exportScene(scene, o);
    std::ifstream in(o.path);
    size_t i = 0;
    double worst = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("v ", 0) != 0) continue;
        std::istringstream ls(line.substr(2));
        glm::dvec3 p;
        ls >> p.x >> p.y >> p.z;
        ASSERT_LT(i, scene.yarns().curves.pointCount());
        worst = std::max(worst, glm::distance(p, scene.yarns().curves.points[i++]));
    }
    EXPECT_EQ(i, scene.yarns().curves.pointCount());
    EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace knit::hard
#endif  // KNIT_HARD_HAVE_EXPORTERS
