// Analytic ply scene: yarns over a plane, helical plies, binding on the plane's two triangles.
#include "knit/synthetic_scene.hpp"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "util/math.hpp"

namespace knit {

Scene makeSyntheticPlyScene(const SyntheticSceneOptions& o) {
    if (o.courses < 1 || !(o.size > 0) || !(o.yarnRadius > 0) || o.plyCount < 1 || o.samplesPerTurn < 3)
        throw Error(
            "synthetic scene: courses and plies must be >= 1, the size and the yarn radius > 0, samples per turn >= 3");
    using util::kPi;
    SceneParts s;
    // Step 1: base plane [0, size]^2 with uv = (x, y) / size, two triangles.
    s.mesh.name = "synthetic-plane";
    s.mesh.positions = {o.offset + glm::dvec3(0, 0, 0), o.offset + glm::dvec3(o.size, 0, 0),
                        o.offset + glm::dvec3(o.size, o.size, 0), o.offset + glm::dvec3(0, o.size, 0)};
    s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    s.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
    s.mesh.faceUvs = s.mesh.faces;
    s.normals.assign(4, glm::dvec3(0, 0, 1));
    s.grid.cellSize = glm::dvec2(o.cellSize);
    s.yarnRadius = o.yarnRadius;
    // Step 2: yarn centrelines along x, their binding and surface normals.
    const double pitch = o.pitch > 0 ? o.pitch : 6.0 * o.yarnRadius;
    const double ds = pitch / o.samplesPerTurn;
    const int n = std::max(2, static_cast<int>(std::ceil(o.size / ds)) + 1);
    const double centre = o.yarnRadius / (1.0 + std::sin(kPi / o.plyCount));
    s.plies.centerRadius = o.plyCount == 1 ? 0.0 : centre;
    s.plies.plyRadius = o.plyCount == 1 ? o.yarnRadius : centre * std::sin(kPi / o.plyCount);
    s.plies.pitch = pitch;
    Binding& b = s.binding;
    for (int c = 0; c < o.courses; ++c) {
        const double y = (c + 0.5) * o.size / o.courses;
        std::vector<glm::dvec3> pts(n);
        for (int i = 0; i < n; ++i) {
            const double x = o.size * i / (n - 1);
            const double z = o.waveAmplitude * std::sin(2 * kPi * x / o.waveLength + c * kPi);
            pts[i] = o.offset + glm::dvec3(x, y, z);
            const double u = x / o.size, v = y / o.size;
            if (u >= v) {
                b.face.push_back(0);
                b.bary.emplace_back(u - v, v);
            } else {
                b.face.push_back(1);
                b.bary.emplace_back(u, v - u);
            }
            b.height.push_back(z);
            b.twist.push_back(0);
            s.yarns.normals.emplace_back(0, 0, 1);
        }
        s.yarns.curves.addCurve(pts.data(), pts.size(), false);
        b.offsets.push_back(static_cast<uint32_t>(b.face.size()));
        b.closed.push_back(0);
        // Step 3: plies c_i(s) = C + R (cos(theta + 2 pi i/n) N + sin(...) B), theta = 2 pi s / pitch.
        for (int p = 0; p < o.plyCount; ++p) {
            std::vector<glm::dvec3> ply(n);
            for (int i = 0; i < n; ++i) {
                const glm::dvec3 t = glm::normalize(pts[std::min(n - 1, i + 1)] - pts[std::max(0, i - 1)]);
                const glm::dvec3 nn = glm::normalize(glm::dvec3(0, 0, 1) - t.z * t);
                const glm::dvec3 bb = glm::cross(t, nn);
                const double theta = 2 * kPi * (o.size * i / (n - 1)) / pitch + 2 * kPi * p / o.plyCount;
                const glm::dvec3 radial = std::cos(theta) * nn + std::sin(theta) * bb;
                ply[i] = pts[i] + s.plies.centerRadius * radial;
                s.plies.radial.push_back(o.plyCount == 1 ? nn : radial);
            }
            s.plies.curves.addCurve(ply.data(), ply.size(), false);
            s.plies.yarnOfCurve.push_back(static_cast<uint32_t>(c));
            s.plies.plyOfCurve.push_back(static_cast<uint8_t>(p));
        }
    }
    return Scene::fromParts(std::move(s));
}

}  // namespace knit
