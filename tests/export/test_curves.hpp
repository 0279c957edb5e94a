// test_curves.hpp — tiny synthetic curves for the export tests (made in code).
#pragma once
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "knit/polylines.hpp"
#include "test_util.hpp"
#include "util/math.hpp"
#include "common/test_paths.hpp"

namespace knit::test {

// A helix of `n` points around the z axis (radius a, rise per turn h), shifted by `offset`.
inline std::vector<glm::dvec3> helix(int n, double a, double h, double turns, glm::dvec3 offset = glm::dvec3(0)) {
    std::vector<glm::dvec3> p;
    for (int i = 0; i < n; ++i) {
        const double t = turns * util::kTwoPi * i / (n - 1);
        p.push_back(offset + glm::dvec3(a * std::cos(t), a * std::sin(t), h * t / util::kTwoPi));
    }
    return p;
}

// A circle of `n` points (each stored once; the curve is closed) in the plane z = offset.z.
inline std::vector<glm::dvec3> circle(int n, double a, glm::dvec3 offset = glm::dvec3(0)) {
    std::vector<glm::dvec3> p;
    for (int i = 0; i < n; ++i) {
        const double t = util::kTwoPi * i / n;
        p.push_back(offset + glm::dvec3(a * std::cos(t), a * std::sin(t), 0.0));
    }
    return p;
}

// Open wavy rows on a plane: `rows` curves of `n` points spaced `spacing` apart, at `offset`.
inline Polylines planeRows(int rows, int n, double spacing, glm::dvec3 offset, double amplitude) {
    Polylines c;
    for (int r = 0; r < rows; ++r) {
        std::vector<glm::dvec3> p;
        for (int i = 0; i < n; ++i) {
            const double x = i * spacing;
            p.push_back(offset + glm::dvec3(x, r * 4.0 * spacing + amplitude * std::sin(x / (3.0 * spacing)),
                                            amplitude * std::cos(x / (2.0 * spacing))));
        }
        c.addCurve(p.data(), p.size(), false);
    }
    return c;
}

// Two open helices and one closed circle: the mixed set most tests use.
inline Polylines mixedCurves(glm::dvec3 offset = glm::dvec3(0)) {
    Polylines c;
    const auto h1 = helix(40, 0.01, 0.004, 3.0, offset);
    const auto h2 = helix(25, 0.006, -0.003, 2.0, offset + glm::dvec3(0.03, 0.0, 0.0));
    const auto c1 = circle(32, 0.02, offset + glm::dvec3(0.0, 0.05, 0.01));
    c.addCurve(h1.data(), h1.size(), false);
    c.addCurve(c1.data(), c1.size(), true);
    c.addCurve(h2.data(), h2.size(), false);
    return c;
}

// A fresh empty folder under the build tree for one test's files.
inline std::string scratchDir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(test::binaryDir()) / "test_output" / "export" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

// Files in a folder (names only), to check that nothing (no temporary file) is left behind.
inline std::vector<std::string> listDir(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    return names;
}

}  // namespace knit::test
