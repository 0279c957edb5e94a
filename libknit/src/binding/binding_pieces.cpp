// binding_pieces.cpp — the rest-pose position of a bound vertex (see binding_pieces.hpp).
#include "binding_pieces.hpp"

#include <glm/geometric.hpp>

namespace knit::impl {

glm::dvec3 RestSurface::position(const BoundVertex& b) const {
    const glm::uvec3 f = mesh.faces[b.face];
    const glm::dvec3 p =
        b.bary.x * mesh.positions[f.x] + b.bary.y * mesh.positions[f.y] + b.bary.z * mesh.positions[f.z];
    const glm::dvec3 n = b.bary.x * normals[f.x] + b.bary.y * normals[f.y] + b.bary.z * normals[f.z];
    const double len = glm::length(n);
    return len > 0 ? p + (b.height / len) * n : p;
}

}  // namespace knit::impl
