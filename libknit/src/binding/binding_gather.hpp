// The binding's per-vertex evaluation (a flat gather), shared by evaluateBinding and the
// strain-aware deformer, which adds its displacement in the same pass over the yarn vertices.
#pragma once
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "knit/binding.hpp"

namespace knit {

// P = sum b_i x_i + h * normalize(sum b_i n_i) for yarn vertex i; nn the interpolated normal.
class BindingGather {
public:
    BindingGather(const Binding& binding, const std::vector<glm::uvec3>& faces,
                  const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals)
        : face_(binding.face.data()),
          bary_(binding.bary.data()),
          height_(binding.height.data()),
          tri_(faces.data()),
          X_(positions.data()),
          N_(normals.data()) {}

    void operator()(size_t i, glm::dvec3& p, glm::dvec3& nn) const {
        const glm::uvec3 f = tri_[face_[i]];
        const double b1 = bary_[i].x, b2 = bary_[i].y, b0 = 1.0 - b1 - b2;
        p = b0 * X_[f.x] + b1 * X_[f.y] + b2 * X_[f.z];
        nn = b0 * N_[f.x] + b1 * N_[f.y] + b2 * N_[f.z];
        const double len2 = glm::dot(nn, nn);
        nn = len2 > 0 ? nn * (1.0 / std::sqrt(len2)) : glm::dvec3(0.0, 0.0, 1.0);
        p += height_[i] * nn;
    }

private:
    const uint32_t* face_;
    const glm::dvec2* bary_;
    const double* height_;
    const glm::uvec3* tri_;
    const glm::dvec3* X_;
    const glm::dvec3* N_;
};

// Sizes `out` for the binding and copies what is the same in every pose (offsets, closed, colour).
inline void prepareMappedYarns(const Binding& binding, MappedYarns& out) {
    const size_t n = binding.vertexCount();
    out.curves.points.resize(n);
    out.curves.offsets = binding.offsets;
    out.curves.closed = binding.closed;
    out.colour = binding.colour;  // constant per pose; empty without colours
    out.twist.clear();            // only a strain deformer gives twist
    out.normals.resize(n);
}

}  // namespace knit
