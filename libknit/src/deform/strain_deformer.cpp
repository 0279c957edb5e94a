// Applying a strain table to one pose (see knit/strain.hpp), in three phases: the map F from
// pattern space of every triangle against the pattern-space layout, and its C = F^T F; both
// averaged to the UV vertices (area weighted); per yarn vertex interpolated barycentrically (so
// strain and displacement are continuous across triangle edges), C looked up in the table and the
// displacement added through the interpolated F (and the normal, for dz).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/error.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

// Strains below this (round-off of an isometric layout) are zero: no displacement, bit for bit.
constexpr double kZeroStrain = 1e-9;

// One triangle's map from pattern space to 3D (columns: where x and y go) and its C = F^T F.
struct FaceStrain {
    glm::dvec3 fx{0.0}, fy{0.0};
    glm::dmat2 C{1.0};
    double area = 0;  // pattern-space area (metres^2, object scale)
    bool valid = false;
};

FaceStrain faceStrain(const glm::dvec2 P[3], const glm::dvec3 X[3]) {
    FaceStrain f;
    const glm::dvec2 e1 = P[1] - P[0], e2 = P[2] - P[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    const double scale = std::max(glm::dot(e1, e1), glm::dot(e2, e2));
    if (!(std::abs(det) > 1e-12 * scale) || !std::isfinite(det)) return f;
    const glm::dvec3 g1 = X[1] - X[0], g2 = X[2] - X[0];
    // F [e1 e2] = [g1 g2]  =>  F = [g1 g2] [e1 e2]^-1.
    const double inv = 1.0 / det;
    f.fx = (e2.y * g1 - e1.y * g2) * inv;
    f.fy = (-e2.x * g1 + e1.x * g2) * inv;
    const double c00 = glm::dot(f.fx, f.fx), c01 = glm::dot(f.fx, f.fy), c11 = glm::dot(f.fy, f.fy);
    f.C = glm::dmat2(c00, c01, c01, c11);
    f.area = 0.5 * std::abs(det);
    // A collapsed 3D triangle has no strain either (its axes have no angle).
    f.valid = std::isfinite(c00) && std::isfinite(c01) && std::isfinite(c11) && c00 > 0 && c11 > 0 &&
              c00 * c11 - c01 * c01 > 1e-12 * c00 * c11;
    return f;
}

bool nearZero(const Strain& s) {
    return std::abs(s.sx) < kZeroStrain && std::abs(s.sa) < kZeroStrain && std::abs(s.sy) < kZeroStrain;
}

}  // namespace

StrainDeformer::StrainDeformer(const BaseMesh& mesh, const Pattern& pattern, const PatternPlacement& placement,
                               const Binding& binding, std::shared_ptr<const StrainTable> table)
    : faces_(mesh.faces),
      faceUvs_(mesh.faceUvs),
      scale_(placement.scale),
      uvCount_(mesh.uvs.size()),
      positionCount_(mesh.positions.size()),
      table_(std::move(table)) {
    if (!table_) throw Error("strain-aware deformation needs a strain table");
    checkStrainTable(*table_, pattern);
    if (binding.source.size() != binding.vertexCount())
        throw Error("strain-aware deformation needs the binding's pattern vertices (Binding::source)");
    const size_t n = pattern.points.size();
    layout_.resize(mesh.uvs.size());
    const glm::dvec2 period = placement.repeats * glm::dvec2(pattern.px, pattern.py) * placement.scale;
    for (size_t i = 0; i < mesh.uvs.size(); ++i) layout_[i] = mesh.uvs[i] * period;
    cellVertex_.resize(binding.vertexCount());
    for (size_t i = 0; i < cellVertex_.size(); ++i) cellVertex_[i] = uint32_t(binding.source[i] % n);
    zero_.resize(n);
    for (size_t v = 0; v < n; ++v) zero_[v] = lookupStrainTable(*table_, uint32_t(v), Strain{});
}

DeformStats StrainDeformer::apply(const Binding& b, const std::vector<glm::dvec3>& positions,
                                  MappedYarns& yarns) const {
    if (b.vertexCount() != cellVertex_.size())
        throw Error("strain-aware deformation: the binding is not the one it was set up with");
    if (yarns.curves.points.size() != b.vertexCount() || yarns.normals.size() != b.vertexCount())
        throw Error("strain-aware deformation: the yarns do not match the binding");
    if (positions.size() != positionCount_)
        throw Error("strain-aware deformation: the pose has " + std::to_string(positions.size()) +
                    " vertices, the rest mesh " + std::to_string(positionCount_));
    // 1. Per triangle.
    std::vector<FaceStrain> faces(faces_.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, faces_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t f = r.begin(); f != r.end(); ++f) {
            const glm::uvec3 p = faces_[f], t = faceUvs_[f];
            const glm::dvec2 P[3] = {layout_[t.x], layout_[t.y], layout_[t.z]};
            const glm::dvec3 X[3] = {positions[p.x], positions[p.y], positions[p.z]};
            faces[f] = faceStrain(P, X);
        }
    });
    // 2. Per UV vertex: the area-weighted mean of its valid triangles' C and F (serial: in face
    //    order, the same sums for any thread count).
    std::vector<glm::dmat2> C(uvCount_, glm::dmat2(0.0));
    std::vector<glm::dvec3> Fx(uvCount_, glm::dvec3(0.0)), Fy(uvCount_, glm::dvec3(0.0));
    std::vector<double> weight(uvCount_, 0.0);
    for (size_t f = 0; f < faces.size(); ++f) {
        if (!faces[f].valid) continue;
        const FaceStrain& fs = faces[f];
        for (int k = 0; k < 3; ++k) {
            const uint32_t u = faceUvs_[f][k];
            C[u] += fs.area * fs.C;
            Fx[u] += fs.area * fs.fx;
            Fy[u] += fs.area * fs.fy;
            weight[u] += fs.area;
        }
    }
    for (size_t u = 0; u < uvCount_; ++u)
        if (weight[u] > 0) {
            C[u] /= weight[u];
            Fx[u] /= weight[u];
            Fy[u] /= weight[u];
        }
    // 3. Per yarn vertex.
    enum : uint8_t { kZero = 0, kMoved = 1, kClamped = 2, kDegenerate = 4 };
    std::vector<uint8_t> flag(b.vertexCount(), kZero);
    const StrainLookup lookup(*table_);
    glm::dvec3* points = yarns.curves.points.data();
    const glm::dvec3* normals = yarns.normals.data();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, b.vertexCount(), 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const uint32_t f = b.face[i];
            const glm::uvec3 t = faceUvs_[f];
            if (!faces[f].valid || !(weight[t.x] > 0 && weight[t.y] > 0 && weight[t.z] > 0)) {
                flag[i] = kDegenerate;
                continue;
            }
            const double b1 = b.bary[i].x, b2 = b.bary[i].y, b0 = 1.0 - b1 - b2;
            const Strain s = strainOf(b0 * C[t.x] + b1 * C[t.y] + b2 * C[t.z]);
            if (nearZero(s)) continue;
            bool clamped = false;
            const glm::dvec4 d = lookup(cellVertex_[i], s, clamped) - zero_[cellVertex_[i]];
            const glm::dvec3 fx = b0 * Fx[t.x] + b1 * Fx[t.y] + b2 * Fx[t.z];
            const glm::dvec3 fy = b0 * Fy[t.x] + b1 * Fy[t.y] + b2 * Fy[t.z];
            points[i] += scale_ * (d.x * fx + d.y * fy + d.z * normals[i]);
            flag[i] = uint8_t(kMoved | (clamped ? kClamped : 0));
        }
    });
    DeformStats stats;
    stats.total = b.vertexCount();
    for (uint8_t fl : flag) {
        stats.vertices += (fl & kMoved) ? 1 : 0;
        stats.clamped += (fl & kClamped) ? 1 : 0;
        stats.degenerate += (fl & kDegenerate) ? 1 : 0;
    }
    return stats;
}

}  // namespace knit
