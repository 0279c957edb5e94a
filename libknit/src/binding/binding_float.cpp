// The per-frame float32 evaluation (knit/binding.hpp): evaluateBindingFloat from the binding's
// own arrays, packBinding and evaluatePackedFloat from one 16-byte record per vertex. Both are
// one kernel (binding_float.hpp): the same float32 arithmetic, so they give the same bits.
//
// Steps: (1) the mesh's positions (minus the origin, in double, then rounded) and normals as
// float32 corners of 32 bytes, in parallel (a mesh is small next to its yarns: the garment's 66k
// vertices against 10M yarn vertices); (2) per yarn vertex, in parallel blocks: gather the
// triangle's corners, interpolate the position and normal, normalize, store the float32
// position (eight at a time in AVX2 where the CPU has it: binding_float_simd.cpp).
#include <memory>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binding_float.hpp"
#include "knit/binding.hpp"
#include "knit/error.hpp"

namespace knit {
namespace impl {

std::unique_ptr<FloatCorner[]> floatCorners(const std::vector<glm::dvec3>& positions,
                                            const std::vector<glm::dvec3>& normals, glm::dvec3 origin) {
    // Not value-initialized: every record is written below (zeroing first cost ~2% of a frame).
    std::unique_ptr<FloatCorner[]> out(new FloatCorner[positions.size()]);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, positions.size(), 8192), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const glm::vec3 p(positions[i] - origin), n(normals[i]);
            out[i] = {{p.x, p.y, p.z, 0.0f}, {n.x, n.y, n.z, 0.0f}};
        }
    });
    return out;
}

}  // namespace impl

namespace {

void requireNormalPerVertex(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals) {
    if (normals.size() != positions.size())
        throw Error("evaluating the binding: " + std::to_string(normals.size()) + " normals for " +
                    std::to_string(positions.size()) + " mesh vertices");
}

// Step 2 over `n` vertices of either layout (a.face / a.bary / a.height or a.packed set).
void evaluateFloatKernel(impl::FloatGatherArrays a, size_t n, const std::vector<glm::uvec3>& faces,
                         const impl::FloatCorner* corners, std::vector<glm::vec3>& out) {
    a.tri = faces.data();
    a.corner = corners;
    out.resize(n);
    glm::vec3* P = out.data();
    const bool simd = impl::evaluateFloatSimdAvailable();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
        size_t i = simd ? impl::evaluateFloatSimd(a, r.begin(), r.end(), P) : r.begin();
        for (; i != r.end(); ++i) P[i] = impl::gatherFloat(a, i);
    });
}

}  // namespace

PackedBinding packBinding(const Binding& binding) {
    const size_t n = binding.vertexCount();
    if (binding.bary.size() != n || binding.height.size() != n)
        throw Error("packing the binding: " + std::to_string(binding.bary.size()) + " barycentrics and " +
                    std::to_string(binding.height.size()) + " heights for " + std::to_string(n) + " vertices");
    PackedBinding out;
    out.vertices.resize(n);
    impl::FloatGatherArrays a;
    a.face = binding.face.data();
    a.bary = binding.bary.data();
    a.height = binding.height.data();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) out.vertices[i] = impl::floatInputs(a, i);
    });
    return out;
}

void evaluateBindingFloat(const Binding& binding, const std::vector<glm::uvec3>& faces,
                          const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                          glm::dvec3 origin, std::vector<glm::vec3>& out) {
    requireNormalPerVertex(positions, normals);
    const std::unique_ptr<impl::FloatCorner[]> corners = impl::floatCorners(positions, normals, origin);
    impl::FloatGatherArrays a;
    a.face = binding.face.data();
    a.bary = binding.bary.data();
    a.height = binding.height.data();
    evaluateFloatKernel(a, binding.vertexCount(), faces, corners.get(), out);
}

void evaluatePackedFloat(const PackedBinding& binding, const std::vector<glm::uvec3>& faces,
                         const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                         glm::dvec3 origin, std::vector<glm::vec3>& out) {
    requireNormalPerVertex(positions, normals);
    const std::unique_ptr<impl::FloatCorner[]> corners = impl::floatCorners(positions, normals, origin);
    impl::FloatGatherArrays a;
    a.packed = binding.vertices.data();
    evaluateFloatKernel(a, binding.vertices.size(), faces, corners.get(), out);
}

}  // namespace knit
