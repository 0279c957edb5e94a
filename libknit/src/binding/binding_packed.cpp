// packBinding and evaluatePackedFloat (knit/binding.hpp): the per-frame float32 evaluation from
// one 16-byte record per vertex.
//
// Steps of evaluatePackedFloat: (1) the mesh's positions (minus the origin, in double, then
// rounded) and normals as float32, in parallel (a mesh is small next to its yarns: the garment's
// 66k vertices against 10M yarn vertices); (2) per yarn vertex, in parallel blocks: gather the
// triangle's corners, interpolate the position and normal, normalize, store the float32 position.
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/binding.hpp"
#include "knit/error.hpp"

namespace knit {

PackedBinding packBinding(const Binding& binding) {
    const size_t n = binding.vertexCount();
    if (binding.bary.size() != n || binding.height.size() != n)
        throw Error("packing the binding: " + std::to_string(binding.bary.size()) + " barycentrics and " +
                    std::to_string(binding.height.size()) + " heights for " + std::to_string(n) + " vertices");
    PackedBinding out;
    out.vertices.resize(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i)
            out.vertices[i] = {binding.face[i], float(binding.bary[i].x), float(binding.bary[i].y),
                               float(binding.height[i])};
    });
    return out;
}

void evaluatePackedFloat(const PackedBinding& binding, const std::vector<glm::uvec3>& faces,
                         const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                         glm::dvec3 origin, std::vector<glm::vec3>& out) {
    if (normals.size() != positions.size())
        throw Error("evaluating the binding: " + std::to_string(normals.size()) + " normals for " +
                    std::to_string(positions.size()) + " mesh vertices");
    // Step 1: the mesh in float32.
    std::vector<glm::vec3> x(positions.size()), nv(positions.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, positions.size(), 8192), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            x[i] = glm::vec3(positions[i] - origin);
            nv[i] = glm::vec3(normals[i]);
        }
    });
    // Step 2: the fused gather.
    const size_t n = binding.vertices.size();
    out.resize(n);
    const PackedBindingVertex* v = binding.vertices.data();
    const glm::uvec3* tri = faces.data();
    const glm::vec3* X = x.data();
    const glm::vec3* N = nv.data();
    glm::vec3* P = out.data();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const PackedBindingVertex b = v[i];
            const glm::uvec3 f = tri[b.face];
            const float b0 = 1.0f - b.b1 - b.b2;
            const glm::vec3 p = b0 * X[f.x] + b.b1 * X[f.y] + b.b2 * X[f.z];
            glm::vec3 nn = b0 * N[f.x] + b.b1 * N[f.y] + b.b2 * N[f.z];
            const float len2 = glm::dot(nn, nn);
            nn = len2 > 0 ? nn * (1.0f / std::sqrt(len2)) : glm::vec3(0.0f, 0.0f, 1.0f);
            P[i] = p + b.height * nn;
        }
    });
}

}  // namespace knit
