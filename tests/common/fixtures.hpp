// Small inputs for the core tests, generated in code.
#pragma once
#include <cmath>
#include <random>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "knit/base_mesh.hpp"
#include "knit/pattern.hpp"
#include "common/test_paths.hpp"

namespace knit::test {

inline std::string sharedPattern(const std::string& file) {
    return std::string(test::sharedDir()) + "/patterns/hylc/" + file;
}

inline const std::vector<std::string>& sharedPatternFiles() {
    static const std::vector<std::string> files = {
        "stockinette.pyp", "stockinette_small.pyp",    "stocktiny.pyp", "stocktiniest.pyp", "basket.pyp",
        "satin.pyp",       "slip_stitch_honeycomb.pyp"};
    return files;
}

enum class Triangulation { Regular, Random, Slivers };

// A planar size x size square at z = 0 with uv = (x, y) / size, triangulated three ways:
// a regular grid; jittered interior vertices with random diagonals; or columns of slivers
// (aspect ratio ~1e6) next to ordinary triangles.
inline BaseMesh planeMesh(Triangulation kind, int n = 8, double size = 0.1, unsigned seed = 7) {
    BaseMesh m;
    m.name = "test-plane";
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.35, 0.35);
    std::vector<double> xs(n + 1);
    for (int i = 0; i <= n; ++i) xs[i] = double(i) / n;
    if (kind == Triangulation::Slivers)
        for (int i = 1; i < n; i += 2) xs[i] = xs[i - 1] + 1e-6 / n;  // near-zero-width columns
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            glm::dvec2 uv(xs[i], double(j) / n);
            if (kind == Triangulation::Random && i > 0 && j > 0 && i < n && j < n)
                uv += glm::dvec2(jitter(rng), jitter(rng)) / double(n);
            m.uvs.push_back(uv);
            m.positions.emplace_back(uv.x * size, uv.y * size, 0.0);
        }
    std::bernoulli_distribution coin(0.5);
    auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (kind == Triangulation::Random && coin(rng)) {
                m.faces.push_back({a, b, d});
                m.faces.push_back({b, c, d});
            } else {
                m.faces.push_back({a, b, c});
                m.faces.push_back({a, c, d});
            }
        }
    m.faceUvs = m.faces;
    return m;
}

}  // namespace knit::test
