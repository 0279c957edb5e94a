// knit/synthetic_scene.hpp — a small analytic ply scene for renderer tests and benchmarks, built
// without the pipeline stages: straight yarns along u over the plane z = 0 (optionally waving up and
// down), each twisted into touching helical plies, with the binding (plane triangles + barycentrics)
// and the UV-grid cell size the two-stage mode needs. Only the parts the renderer reads are
// filled (Scene::fromParts): mesh, normals, grid.cellSize, yarnRadius, binding, yarns, plies.
#pragma once
#include <glm/vec3.hpp>

#include "knit/scene.hpp"

namespace knit {

struct SyntheticSceneOptions {
    int courses = 4;             // yarns along x, evenly spread over y
    double size = 0.01;          // side of the square base plane (m), uv = (x, y) / size
    double yarnRadius = 0.0005;  // m
    int plyCount = 2;
    double pitch = 0;  // ply turn length; 0 = 6 yarn radii
    int samplesPerTurn = 16;
    double waveAmplitude = 0;  // yarn height z = A sin(2 pi x / waveLength + course * pi)
    double waveLength = 0.005;
    double cellSize = 0.125;  // UV size of a grid cell
    glm::dvec3 offset{0.0};   // translation of the whole scene (precision far from the origin)
};

Scene makeSyntheticPlyScene(const SyntheticSceneOptions& options);

}  // namespace knit
