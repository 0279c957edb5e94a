// Applying a strain table to one pose (see knit/strain.hpp), in three phases: the map F from
// pattern space of every triangle against the pattern-space layout, and its C = F^T F; both
// averaged to the UV vertices (area weighted); per yarn vertex interpolated barycentrically (so
// strain and displacement are continuous across triangle edges), C looked up in the table and the
// displacement added through the interpolated F (and the normal, for dz). The last phase runs in
// the same pass as the binding's gather (evaluate), so a frame reads and writes its millions of
// yarn points once; at the UV vertices (the garment case) inside the gather's AVX2 kernel, four
// yarn vertices at a time (strain_displace_simd.cpp), counted per triangle. The twist (for the
// plies) is looked up where the displacements are and only when asked for.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "knit/error.hpp"
#include "binding/binding_evaluate_simd.hpp"
#include "binding/binding_gather.hpp"
#include "knit/strain.hpp"
#include "strain_displace.hpp"
#include "strain_lookup.hpp"

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

constexpr uint8_t kZero = impl::kStrainZero, kMoved = impl::kStrainMoved, kClamped = impl::kStrainClamped,
                  kDegenerate = impl::kStrainDegenerate;

void count(uint8_t flag, DeformStats& stats) {
    stats.vertices += (flag & kMoved) ? 1 : 0;
    stats.clamped += (flag & kClamped) ? 1 : 0;
    stats.degenerate += (flag & kDegenerate) ? 1 : 0;
}

bool nearZero(const Strain& s) {
    return std::abs(s.sx) < kZeroStrain && std::abs(s.sa) < kZeroStrain && std::abs(s.sy) < kZeroStrain;
}

}  // namespace

StrainDeformer::StrainDeformer(const BaseMesh& mesh, const Pattern& pattern, const PatternPlacement& placement,
                               const Binding& binding, std::shared_ptr<const StrainTable> table, StrainLookupSite site)
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
    faceVertices_.assign(faces_.size(), 0);
    for (const uint32_t f : binding.face) ++faceVertices_[f];
    findBoundaryEnds(pattern, binding);
    zero_.resize(n);
    const StrainLookup lookup(*table_);  // the same arithmetic as the per-frame lookups
    bool clamped = false;
    for (size_t v = 0; v < n; ++v) zero_[v] = lookup(uint32_t(v), Strain{}, clamped);
    for (size_t r = 0; r < table_->data.size() / 4 && !hasTwist_; ++r)
        hasTwist_ = double(table_->data[4 * r + 3]) != zero_[r / table_->samples()].w;
    // (Rows of the per-UV-vertex displacements are indexed in 32 bits.)
    atMeshVertices_ = uvCount_ * n < std::numeric_limits<uint32_t>::max() &&
                      (site == StrainLookupSite::MeshVertices ||
                       (site == StrainLookupSite::Auto && uvCount_ * n < binding.vertexCount()));
}

// An open yarn's end that repeats its neighbour's tiled vertex was inserted on the mesh's boundary
// (binding_cut.cpp: a crossing takes the source of the vertex it leaves). Its rest position in
// pattern space against that vertex's gives the pattern edge it lies on (the best aligned of the
// vertex's two) and how far along it.
void StrainDeformer::findBoundaryEnds(const Pattern& pattern, const Binding& b) {
    const PatternAdjacency adjacency = buildAdjacency(pattern);
    const auto rest = [&](size_t i) {
        const glm::uvec3 t = faceUvs_[b.face[i]];
        const double b1 = b.bary[i].x, b2 = b.bary[i].y;
        return (1.0 - b1 - b2) * layout_[t.x] + b1 * layout_[t.y] + b2 * layout_[t.z];
    };
    const auto end = [&](size_t i, size_t inside) {
        if (b.source[i] != b.source[inside]) return;
        const uint32_t v = cellVertex_[i];
        const glm::dvec2 r = rest(i) - rest(inside);
        BoundaryEnd best;
        double bestCos = 0;
        for (const PatternNeighbor& w : adjacency.slots[v]) {
            if (w.v < 0) continue;
            const glm::dvec3& q = pattern.points[size_t(w.v)];
            const glm::dvec2 e =
                scale_ * (glm::dvec2(q.x + w.dx * pattern.px, q.y + w.dy * pattern.py) - glm::dvec2(pattern.points[v]));
            const double ee = glm::dot(e, e), re = glm::dot(r, e);
            if (!(ee > 0) || !(re > 0)) continue;
            const double cosine = re / std::sqrt(ee * glm::dot(r, r));
            if (cosine > bestCos) {
                bestCos = cosine;
                best = {uint32_t(i), uint32_t(w.v), std::min(1.0, re / ee)};
            }
        }
        if (bestCos > 0) ends_.push_back(best);
    };
    for (size_t y = 0; y < b.yarnCount(); ++y) {
        const size_t first = b.offsets[y], last = b.offsets[y + 1];
        if (b.closed[y] || last - first < 2) continue;
        end(first, first + 1);
        end(last - 1, last - 2);
    }
}

// Per UV vertex the area-weighted mean of its valid triangles' C and F, and per triangle whether
// its yarn vertices have a strain (the triangle and its three UV vertices).
struct StrainDeformer::Pose {
    struct Uv {
        double c00 = 0, c01 = 0, c11 = 0;
        glm::dvec3 fx{0.0}, fy{0.0};
    };
    std::vector<Uv> uv;
    std::vector<uint8_t> ok;
};

StrainDeformer::Pose StrainDeformer::pose(const Binding& b, const std::vector<glm::dvec3>& positions) const {
    if (b.vertexCount() != cellVertex_.size())
        throw Error("strain-aware deformation: the binding is not the one it was set up with");
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
    // 2. Per UV vertex (serial: in face order, the same sums for any thread count).
    Pose pose;
    pose.uv.assign(uvCount_, Pose::Uv{});
    std::vector<double> weight(uvCount_, 0.0);
    for (size_t f = 0; f < faces.size(); ++f) {
        if (!faces[f].valid) continue;
        const FaceStrain& fs = faces[f];
        for (int k = 0; k < 3; ++k) {
            const uint32_t u = faceUvs_[f][k];
            Pose::Uv& v = pose.uv[u];
            v.c00 += fs.area * fs.C[0][0];
            v.c01 += fs.area * fs.C[1][0];
            v.c11 += fs.area * fs.C[1][1];
            v.fx += fs.area * fs.fx;
            v.fy += fs.area * fs.fy;
            weight[u] += fs.area;
        }
    }
    for (size_t u = 0; u < uvCount_; ++u)
        if (weight[u] > 0) {
            Pose::Uv& v = pose.uv[u];
            v.c00 /= weight[u];
            v.c01 /= weight[u];
            v.c11 /= weight[u];
            v.fx /= weight[u];
            v.fy /= weight[u];
        }
    pose.ok.resize(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
        const glm::uvec3 t = faceUvs_[f];
        pose.ok[f] = faces[f].valid && weight[t.x] > 0 && weight[t.y] > 0 && weight[t.z] > 0;
    }
    return pose;
}

// Per pose at the UV vertices (MeshVertices): the displacement rows, the twist rows (when asked
// and the table has twist) and per triangle its corners (impl::StrainCorners).
struct StrainDeformer::MeshRows {
    std::vector<glm::dvec4> d;
    std::vector<double> twist;
    std::vector<impl::StrainCorners> corners;

    impl::StrainRows view(const std::vector<uint32_t>& cellVertex) const {
        return {corners.data(), d.data(), cellVertex.data()};
    }
};

void StrainDeformer::meshDisplacements(const Pose& pose, bool withTwist, MeshRows& rows,
                                       std::vector<uint8_t>& flags) const {
    const size_t n = zero_.size();
    rows.d.resize(uvCount_ * n);
    if (withTwist) rows.twist.assign(uvCount_ * n, 0.0);
    flags.assign(uvCount_, kZero);
    const StrainLookup lookup(*table_);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, uvCount_, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t u = r.begin(); u != r.end(); ++u) {
            const Pose::Uv& uv = pose.uv[u];
            glm::dvec4* row = &rows.d[u * n];
            const Strain s = strainOfC(uv.c00, uv.c01, uv.c11);
            if (nearZero(s)) {  // also a UV vertex without valid triangles (its C is zero: never read)
                std::fill(row, row + n, glm::dvec4(0.0));
                continue;
            }
            bool clamped = false;
            const StrainLookup::Cell cell = lookup.locate(s, clamped);
            double* twist = rows.twist.empty() ? nullptr : &rows.twist[u * n];
            for (size_t v = 0; v < n; ++v) {
                const glm::dvec4 e = lookup.blend(cell, lookup.vertexOffset(uint32_t(v))) - zero_[v];
                row[v] = glm::dvec4(scale_ * (e.x * uv.fx + e.y * uv.fy), scale_ * e.z);
                if (twist) twist[v] = e.w;
            }
            flags[u] = uint8_t(kMoved | (clamped ? kClamped : 0));
        }
    });
}

StrainDeformer::MeshRows StrainDeformer::meshRows(const Pose& pose, bool withTwist) const {
    MeshRows rows;
    std::vector<uint8_t> flags;
    meshDisplacements(pose, withTwist && hasTwist_, rows, flags);
    const auto cells = uint32_t(zero_.size());
    rows.corners.resize(faceUvs_.size());
    for (size_t f = 0; f < faceUvs_.size(); ++f) {
        const glm::uvec3 t = faceUvs_[f];
        rows.corners[f] = {{t.x * cells, t.y * cells, t.z * cells},
                           pose.ok[f] ? uint8_t(flags[t.x] | flags[t.y] | flags[t.z]) : uint8_t(kDegenerate)};
    }
    return rows;
}

// The same counts as counting every yarn vertex by its triangle's flag.
DeformStats StrainDeformer::rowStats(const MeshRows& rows) const {
    DeformStats stats;
    for (size_t f = 0; f < rows.corners.size(); ++f) {
        const uint8_t flag = rows.corners[f].flag;
        const size_t k = faceVertices_[f];
        stats.vertices += (flag & kMoved) ? k : 0;
        stats.clamped += (flag & kClamped) ? k : 0;
        stats.degenerate += (flag & kDegenerate) ? k : 0;
    }
    return stats;
}

template <class Point, class Displacement>
void StrainDeformer::moveEnds(const Point& point, const Displacement& displacement) const {
    // The same arithmetic whether `point` gathers or reads.
    for (const BoundaryEnd& end : ends_) {
        glm::dvec3 p, n, e0, e1;
        glm::dvec3& out = point(end.vertex, p, n);
        if (!(displacement(end.vertex, cellVertex_[end.vertex], n, e0) & kMoved)) continue;
        displacement(end.vertex, end.beyond, n, e1);
        out += end.t * (e1 - e0);
    }
}

// 3. Per yarn vertex interpolating its triangle's UV vertices' displacements; `block` does the
// first vertices of each range (four at a time), this loop the rest.
template <class Point, class Block>
DeformStats StrainDeformer::runAtMeshVertices(const Binding& b, const MeshRows& rows, Point point, Block block) const {
    const impl::StrainRows view = rows.view(cellVertex_);
    const uint32_t* face = b.face.data();
    const glm::dvec2* bary = b.bary.data();
    const auto displacement = [&](size_t i, uint32_t v, const glm::dvec3& n, glm::dvec3& out) {
        return impl::strainDisplacement(view, face[i], bary[i], v, n, out);
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, b.vertexCount(), 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = block(r.begin(), r.end(), view); i != r.end(); ++i) {
            glm::dvec3 p, n, e;
            glm::dvec3& out = point(i, p, n);
            out = (displacement(i, cellVertex_[i], n, e) & kMoved) ? p + e : p;
        }
    });
    moveEnds(point, displacement);
    return rowStats(rows);
}

// 3. Per yarn vertex looking its strain up (the reference).
template <class Point>
DeformStats StrainDeformer::runAtYarnVertices(const Binding& b, const Pose& pose, Point point) const {
    const uint32_t* face = b.face.data();
    const glm::dvec2* bary = b.bary.data();
    const StrainLookup lookup(*table_);
    // The displacement of yarn vertex i (normal n) as cell vertex v, into `out`; returns its flag
    // (no displacement unless kMoved).
    const auto displacement = [&](size_t i, uint32_t v, const glm::dvec3& n, glm::dvec3& out) -> uint8_t {
        const uint32_t f = face[i];
        if (!pose.ok[f]) return kDegenerate;
        const glm::uvec3 t = faceUvs_[f];
        const Pose::Uv &u0 = pose.uv[t.x], &u1 = pose.uv[t.y], &u2 = pose.uv[t.z];
        const double b1 = bary[i].x, b2 = bary[i].y, b0 = 1.0 - b1 - b2;
        const Strain s = strainOfC(b0 * u0.c00 + b1 * u1.c00 + b2 * u2.c00, b0 * u0.c01 + b1 * u1.c01 + b2 * u2.c01,
                                   b0 * u0.c11 + b1 * u1.c11 + b2 * u2.c11);
        if (nearZero(s)) return kZero;
        bool clamped = false;
        const glm::dvec4 d = lookup.at(lookup.vertexOffset(v), s, clamped) - zero_[v];
        const glm::dvec3 fx = b0 * u0.fx + b1 * u1.fx + b2 * u2.fx;
        const glm::dvec3 fy = b0 * u0.fy + b1 * u1.fy + b2 * u2.fy;
        out = scale_ * (d.x * fx + d.y * fy + d.z * n);
        return uint8_t(kMoved | (clamped ? kClamped : 0));
    };
    const auto pass = [&](const tbb::blocked_range<size_t>& r, DeformStats stats) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            glm::dvec3 p, n, e;
            glm::dvec3& out = point(i, p, n);
            const uint8_t flag = displacement(i, cellVertex_[i], n, e);
            out = (flag & kMoved) ? p + e : p;
            count(flag, stats);
        }
        return stats;
    };
    const auto sum = [](DeformStats a, const DeformStats& c) {
        a.vertices += c.vertices;
        a.clamped += c.clamped;
        a.degenerate += c.degenerate;
        return a;
    };
    const DeformStats stats =
        tbb::parallel_reduce(tbb::blocked_range<size_t>(0, b.vertexCount(), 16384), DeformStats{}, pass, sum);
    moveEnds(point, displacement);
    return stats;
}

template <class Point, class Block>
DeformStats StrainDeformer::run(const Binding& b, const Pose& pose, Point point, Block block, MappedYarns& yarns,
                                bool withTwist) const {
    DeformStats stats;
    yarns.twist.clear();
    if (atMeshVertices_) {
        const MeshRows rows = meshRows(pose, withTwist);
        stats = runAtMeshVertices(b, rows, point, block);
        if (withTwist) twist(b, rows, yarns);
    } else {
        stats = runAtYarnVertices(b, pose, point);
        if (withTwist) twist(b, pose, yarns);
    }
    stats.total = b.vertexCount();
    return stats;
}

// Per yarn vertex, the table read at its interpolated strain (as runAtYarnVertices) for the twist
// column alone; zero where the strain is zero or undefined.
void StrainDeformer::twist(const Binding& b, const Pose& pose, MappedYarns& yarns) const {
    yarns.twist.clear();
    if (!hasTwist_) return;
    yarns.twist.resize(b.vertexCount());
    const StrainLookup lookup(*table_);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, b.vertexCount(), 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            yarns.twist[i] = 0.0F;
            const uint32_t f = b.face[i];
            if (!pose.ok[f]) continue;
            const glm::uvec3 t = faceUvs_[f];
            const Pose::Uv &u0 = pose.uv[t.x], &u1 = pose.uv[t.y], &u2 = pose.uv[t.z];
            const double b1 = b.bary[i].x, b2 = b.bary[i].y, b0 = 1.0 - b1 - b2;
            const Strain s = strainOfC(b0 * u0.c00 + b1 * u1.c00 + b2 * u2.c00, b0 * u0.c01 + b1 * u1.c01 + b2 * u2.c01,
                                       b0 * u0.c11 + b1 * u1.c11 + b2 * u2.c11);
            if (nearZero(s)) continue;
            bool clamped = false;
            const uint32_t v = cellVertex_[i];
            yarns.twist[i] = float(lookup.at(lookup.vertexOffset(v), s, clamped).w - zero_[v].w);
        }
    });
}

// Per yarn vertex, its triangle's UV vertices' twist rows interpolated (as the displacements);
// zero where the triangle did not move.
void StrainDeformer::twist(const Binding& b, const MeshRows& rows, MappedYarns& yarns) const {
    yarns.twist.clear();
    if (rows.twist.empty()) return;
    yarns.twist.resize(b.vertexCount());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, b.vertexCount(), 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const impl::StrainCorners& c = rows.corners[b.face[i]];
            const uint32_t v = cellVertex_[i];
            const double b1 = b.bary[i].x, b2 = b.bary[i].y, b0 = 1.0 - b1 - b2;
            yarns.twist[i] = (c.flag & kMoved) ? float(b0 * rows.twist[c.row[0] + v] + b1 * rows.twist[c.row[1] + v] +
                                                       b2 * rows.twist[c.row[2] + v])
                                               : 0.0F;
        }
    });
}

DeformStats StrainDeformer::apply(const Binding& b, const std::vector<glm::dvec3>& positions,
                                  MappedYarns& yarns) const {
    if (yarns.curves.points.size() != b.vertexCount() || yarns.normals.size() != b.vertexCount())
        throw Error("strain-aware deformation: the yarns do not match the binding");
    const Pose p = pose(b, positions);
    glm::dvec3* points = yarns.curves.points.data();
    const glm::dvec3* normals = yarns.normals.data();
    const auto point = [points, normals](size_t i, glm::dvec3& q, glm::dvec3& n) -> glm::dvec3& {
        q = points[i];
        n = normals[i];
        return points[i];
    };
    const auto scalar = [](size_t begin, size_t, const impl::StrainRows&) { return begin; };
    return run(b, p, point, scalar, yarns, true);
}

// The gather and the displacement in one pass; at the UV vertices, four yarn vertices at a time
// in AVX2 where the CPU has it (impl::evaluateDisplacedSimd, bit for bit the scalar loop's).
DeformStats StrainDeformer::evaluate(const Binding& b, const std::vector<glm::dvec3>& positions,
                                     const std::vector<glm::dvec3>& normals, MappedYarns& out, bool withTwist) const {
    if (normals.size() != positionCount_)
        throw Error("strain-aware deformation: the pose has " + std::to_string(positions.size()) + " vertices but " +
                    std::to_string(normals.size()) + " normals");
    const Pose p = pose(b, positions);
    prepareMappedYarns(b, out);
    const BindingGather gather(b, faces_, positions, normals);
    glm::dvec3* points = out.curves.points.data();
    glm::dvec3* outNormals = out.normals.data();
    const auto point = [&gather, points, outNormals](size_t i, glm::dvec3& q, glm::dvec3& n) -> glm::dvec3& {
        gather(i, q, n);
        outNormals[i] = n;
        return points[i];
    };
    const impl::GatherArrays arrays{b.face.data(), b.bary.data(),    b.height.data(),
                                    faces_.data(), positions.data(), normals.data()};
    const bool simd = impl::evaluateSimdAvailable();
    const auto block = [&](size_t begin, size_t end, const impl::StrainRows& rows) {
        return simd ? impl::evaluateDisplacedSimd(arrays, rows, begin, end, points, outNormals) : begin;
    };
    return run(b, p, point, block, out, withTwist);
}

}  // namespace knit
