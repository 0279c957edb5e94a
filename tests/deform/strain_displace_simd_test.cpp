// The strain deformer's AVX2 kernel (the binding's gather with the displacement at the UV vertices
// added in registers) is the scalar gather followed by the scalar displacement bit for bit: on a
// moved pose, with normals that cancel or vanish, triangles moved and not, and for any start and
// end of a range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "binding/binding_evaluate_simd.hpp"
#include "binding/binding_gather.hpp"
#include "deform/strain_displace.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

bool same(const glm::dvec3& a, const glm::dvec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Made-up rows: every triangle's corners somewhere in the rows, flags cycling through zero, moved,
// moved and clamped, degenerate; displacements of a few millimetres with a normal part.
struct Rows {
    std::vector<impl::StrainCorners> corners;
    std::vector<glm::dvec4> d;
    std::vector<uint32_t> cellVertex;
};

Rows madeUpRows(size_t faces, size_t yarnVertices, uint32_t cells) {
    Rows r;
    const uint32_t uvs = 97;
    for (uint32_t k = 0; k < uvs * cells; ++k)
        r.d.emplace_back(1e-3 * std::sin(k), 2e-3 * std::cos(3.0 * k), 1e-3 * std::sin(0.7 * k), 5e-4 * std::cos(k));
    const uint8_t flags[4] = {impl::kStrainZero, impl::kStrainMoved, impl::kStrainMoved | impl::kStrainClamped,
                              impl::kStrainDegenerate};
    for (uint32_t f = 0; f < faces; ++f)
        r.corners.push_back(
            {{(f % uvs) * cells, ((7 * f + 3) % uvs) * cells, ((13 * f + 5) % uvs) * cells}, flags[(f / 3) % 4]});
    for (size_t i = 0; i < yarnVertices; ++i) r.cellVertex.push_back(uint32_t((5 * i) % cells));
    return r;
}

TEST(StrainDisplaceSimd, kernelIsTheScalarGatherAndDisplacementBitForBit) {
    if (!impl::evaluateSimdAvailable()) GTEST_SKIP() << "no AVX2 (or KNIT_SIMD=0)";
    SceneOptions o;
    o.placement.repeats = {12, 12};
    o.buildPlies = false;
    ProceduralMeshOptions mo;
    mo.resU = mo.resV = 16;
    const Scene s = buildScene(generateStockinette(), makeDrape(mo), o);
    const Binding& b = s.binding();
    std::vector<glm::dvec3> moved = s.mesh().positions;
    for (glm::dvec3& x : moved) x += glm::dvec3(0.0, 0.0, 0.05 * std::sin(8.0 * x.x));
    std::vector<glm::dvec3> normals = vertexNormals(moved, s.mesh().faces);
    for (size_t v = 0; v < normals.size(); v += 3) normals[v] = -normals[v];  // some sums near zero
    const Rows rows = madeUpRows(s.mesh().faces.size(), b.vertexCount(), 24);
    const impl::StrainRows view{rows.corners.data(), rows.d.data(), rows.cellVertex.data()};
    const impl::GatherArrays arrays{b.face.data(),         b.bary.data(), b.height.data(),
                                    s.mesh().faces.data(), moved.data(),  normals.data()};
    const BindingGather gather(b, s.mesh().faces, moved, normals);
    size_t displaced = 0;
    for (size_t begin : {size_t(0), size_t(1), size_t(3)}) {
        const size_t end = b.vertexCount() - begin;
        std::vector<glm::dvec3> P(end + 1, glm::dvec3(7.0)), N(end + 1, glm::dvec3(7.0));
        const size_t done = impl::evaluateDisplacedSimd(arrays, view, begin, end, P.data(), N.data());
        EXPECT_EQ(done, begin + (end - begin) / 4 * 4);
        size_t differ = 0;
        for (size_t i = 0; i <= end; ++i) {
            glm::dvec3 p(7.0), n(7.0), e;
            if (i >= begin && i < done) {
                gather(i, p, n);
                if (impl::strainDisplacement(view, b.face[i], b.bary[i], rows.cellVertex[i], n, e) &
                    impl::kStrainMoved) {
                    p += e;
                    ++displaced;
                }
            }
            differ += !same(P[i], p) || !same(N[i], n);
        }
        EXPECT_EQ(differ, 0u) << "from " << begin;
    }
    EXPECT_GT(displaced, b.vertexCount());  // about half of them, three times
}

}  // namespace
}  // namespace knit
