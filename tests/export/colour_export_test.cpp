// Yarn colours (a pattern's colour layer) in the exports: COLOR_0 on glTF tubes (plain, Draco)
// and line strips, vertex colours in PLY, per-curve colours in pbrt.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "export/export_helpers.hpp"
#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/export.hpp"

namespace knit {
namespace {

// An open helix (first half red, second half blue) and a closed circle (linear green 0.5).
struct ColouredCurves {
    Polylines curves;
    std::vector<glm::vec3> colours;
};

ColouredCurves colouredCurves() {
    ColouredCurves c;
    const auto h = test::helix(20, 0.01, 0.004, 2.0);
    c.curves.addCurve(h.data(), h.size(), false);
    const auto o = test::circle(16, 0.01, glm::dvec3(0.05, 0, 0));
    c.curves.addCurve(o.data(), o.size(), true);
    for (size_t i = 0; i < h.size(); ++i) c.colours.push_back(i < 10 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1));
    c.colours.insert(c.colours.end(), o.size(), glm::vec3(0, 0.5f, 0));
    return c;
}

ExportStats write(const ColouredCurves& c, ExportOptions o) {
    ExportInput in;
    in.curves = &c.curves;
    in.radius = 0.001;
    in.colours = &c.colours;
    return exportCurves(in, o);
}

// The colour byte the exporter stores for a linear value, read back normalized.
double stored(float v) { return std::lround(v * 255.0f) / 255.0; }

// Expected tube vertex colours in sweep order (rings of sides + 1 vertices per point, a closed
// curve one extra ring, open curves two caps of sides + 1 vertices).
std::vector<glm::vec3> expectedTubeColours(const ColouredCurves& c, int sides) {
    std::vector<glm::vec3> out;
    const Polylines& p = c.curves;
    for (size_t k = 0; k < p.curveCount(); ++k) {
        const uint32_t n = p.size(k), b = p.begin(k);
        const size_t rings = p.isClosed(k) ? n + 1 : n;
        for (size_t i = 0; i < rings; ++i) out.insert(out.end(), size_t(sides) + 1, c.colours[b + i % n]);
        if (!p.isClosed(k)) {
            out.insert(out.end(), size_t(sides) + 1, c.colours[b]);
            out.insert(out.end(), size_t(sides) + 1, c.colours[b + n - 1]);
        }
    }
    return out;
}

// Every COLOR_0 value of the file's primitives in order, as RGBA.
std::vector<glm::dvec4> readColours(const gltf::Document& m, size_t& primitivesWithout) {
    std::vector<glm::dvec4> out;
    primitivesWithout = 0;
    for (const auto& inst : m.meshInstances())
        for (const auto& p : m.primitives(inst.mesh)) {
            if (!m.attribute(p, "COLOR_0")) {
                ++primitivesWithout;
                continue;
            }
            const auto v = test::readAttribute(m, p, "COLOR_0");
            for (size_t i = 0; i + 3 < v.size(); i += 4) out.emplace_back(v[i], v[i + 1], v[i + 2], v[i + 3]);
        }
    return out;
}

TEST(ColourExport, tubeGlbCarriesEachPointsColourInColor0) {
    const std::string dir = test::scratchDir("colour_tubes");
    const ColouredCurves c = colouredCurves();
    ExportOptions o = test::tubeOptions(dir + "/t.glb");
    write(c, o);
    test::expectGltfValid(o.path);
    size_t without = 0;
    const std::vector<glm::dvec4> got = readColours(test::loadGltf(o.path), without);
    EXPECT_EQ(without, 0u);
    const std::vector<glm::vec3> want = expectedTubeColours(c, o.sides);
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i)
        ASSERT_EQ(got[i], glm::dvec4(stored(want[i].r), stored(want[i].g), stored(want[i].b), 1.0)) << i;
}

TEST(ColourExport, lineStripsCarryColor0AndAClosedCurveRepeatsItsFirstColour) {
    const std::string dir = test::scratchDir("colour_lines");
    const ColouredCurves c = colouredCurves();
    ExportOptions o;
    o.path = dir + "/l.glb";
    o.what = ExportWhat::Plies;
    write(c, o);
    test::expectGltfValid(o.path);
    size_t without = 0;
    const std::vector<glm::dvec4> got = readColours(test::loadGltf(o.path), without);
    EXPECT_EQ(without, 0u);
    ASSERT_EQ(got.size(), 20u + 17u);
    EXPECT_EQ(got[0], glm::dvec4(1, 0, 0, 1));
    EXPECT_EQ(got[19], glm::dvec4(0, 0, 1, 1));
    for (size_t i = 20; i < got.size(); ++i) ASSERT_EQ(got[i], glm::dvec4(0, stored(0.5f), 0, 1)) << i;
}

TEST(ColourExport, dracoTubesDeclareColor0AndStayValid) {
    const std::string dir = test::scratchDir("colour_draco");
    const ColouredCurves c = colouredCurves();
    ExportOptions o = test::tubeOptions(dir + "/d.glb");
    o.draco = true;
    write(c, o);
    test::expectGltfValid(o.path);
    const gltf::Document m = test::loadGltf(o.path);
    for (const auto& inst : m.meshInstances())
        for (const auto& p : m.primitives(inst.mesh)) EXPECT_TRUE(m.attribute(p, "COLOR_0").has_value());
}

TEST(ColourExport, yarnColorsFlagWinsOverPatternColours) {
    const std::string dir = test::scratchDir("colour_flag");
    const ColouredCurves c = colouredCurves();
    ExportOptions o = test::tubeOptions(dir + "/f.glb");
    o.yarnColors = true;
    write(c, o);
    size_t without = 0;
    const std::vector<glm::dvec4> got = readColours(test::loadGltf(o.path), without);
    ASSERT_FALSE(got.empty());
    // The palette gives the whole first curve one colour; the pattern would give it two.
    const size_t firstCurve = (20 + 2) * size_t(o.sides + 1);
    for (size_t i = 0; i < firstCurve; ++i) ASSERT_EQ(got[i], got[0]) << i;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The coloured curves exported as plies to `name` in a scratch folder; the file's bytes.
std::string exportedCurves(const std::string& name) {
    ExportOptions o;
    o.path = test::scratchDir("colour_" + name) + "/" + name;
    o.what = ExportWhat::Plies;
    write(colouredCurves(), o);
    return readText(o.path);
}

TEST(ColourExport, plyCurveVerticesCarrySrgbColourBytes) {
    const std::string text = exportedCurves("c.ply");
    EXPECT_NE(text.find("property uchar red\nproperty uchar green\nproperty uchar blue\n"), std::string::npos);
    // Vertex records: double x y z, then red green blue.
    const size_t body = text.find("end_header\n") + 11, record = 3 * 8 + 3;
    ASSERT_LT(body + 37 * record, text.size());
    auto rgb = [&](size_t v) {
        const char* c = text.data() + body + v * record + 24;
        return glm::ivec3(uint8_t(c[0]), uint8_t(c[1]), uint8_t(c[2]));
    };
    EXPECT_EQ(rgb(0), glm::ivec3(255, 0, 0));
    EXPECT_EQ(rgb(19), glm::ivec3(0, 0, 255));
    EXPECT_EQ(rgb(20), glm::ivec3(0, 188, 0));  // linear 0.5 is sRGB 0.7354
}

TEST(ColourExport, pbrtCurvesCarryTheirColourAsReflectance) {
    const std::string text = exportedCurves("c.pbrt");
    EXPECT_NE(text.find("\"rgb reflectance\" [ 1 0 0 ]"), std::string::npos);
    EXPECT_NE(text.find("\"rgb reflectance\" [ 0 0.5 0 ]"), std::string::npos);
}

}  // namespace
}  // namespace knit
