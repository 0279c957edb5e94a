// gltf_read.hpp — read back glTF / GLB files written by the exporter with the project's one glTF
// reader (gltf::Document, libknit/src/internal/io/gltf_document.hpp: container, buffers, accessors, node
// tree), plus the checks only a test makes (GLB chunk alignment) and curve comparisons.
// KHR_draco_mesh_compression primitives are decoded in the tests with the Draco library, on the
// buffer-view bytes the document gives. The exports are also checked by the Khronos validator
// (gltf_validator.hpp), which is independent of this reader.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "io/gltf_document.hpp"
#include "knit/polylines.hpp"

#include "export/test_curves.hpp"

namespace knit::test {

// A GLB's header and chunks are what the writer promises: the header's length is the file's,
// chunk lengths are multiples of 4, and a chunk after the JSON is the BIN chunk.
inline void expectAlignedGlb(const gltf::Document& d, const std::string& path) {
    const gltf::GlbLayout& g = d.glbLayout();
    if (!g.glb) return;
    EXPECT_EQ(g.length, readBytes(path).size()) << path;
    EXPECT_EQ(g.jsonLength % 4, 0u) << path;
    if (g.secondChunk) {
        EXPECT_EQ(g.secondType, 0x004E4942u) << path << ": the second chunk is not BIN";
        EXPECT_EQ(g.secondLength % 4, 0u) << path;
    }
}

// The file at `path` (.gltf with its buffers, or .glb), its GLB layout checked.
inline gltf::Document loadGltf(const std::string& path) {
    gltf::Document d = gltf::Document::load(path);
    expectAlignedGlb(d, path);
    return d;
}

// All values of an accessor as doubles (count x components), normalized integers mapped to
// [-1, 1] / [0, 1] as the glTF spec defines, raw integers kept as integers.
inline std::vector<double> readAccessor(const gltf::Document& d, size_t index) {
    return d.accessor(index, "test").values();
}

// The values of attribute `name` of primitive `p` (a test failure when it has none).
inline std::vector<double> readAttribute(const gltf::Document& d, const gltf::Primitive& p, const char* name) {
    const std::optional<size_t> a = d.attribute(p, name);
    if (!a) {
        ADD_FAILURE() << p.what << " has no " << name;
        return {};
    }
    return readAccessor(d, *a);
}

// World-space positions of one primitive's POSITION accessor.
inline std::vector<glm::dvec3> worldPositions(const gltf::Document& d, const gltf::Primitive& p,
                                              const glm::dmat4& world) {
    const std::vector<double> v = readAttribute(d, p, "POSITION");
    std::vector<glm::dvec3> out(v.size() / 3);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = glm::dvec3(world * glm::dvec4(v[3 * i], v[3 * i + 1], v[3 * i + 2], 1.0));
    return out;
}

// Largest distance between the curves of a curve export (one LINE_STRIP primitive per curve, in
// file order; a closed curve repeats its first point) and the exported curves `c`. Adds a test
// failure when the curve or point counts differ.
inline double worstCurveDeviation(const gltf::Document& d, const Polylines& c) {
    double worst = 0;
    size_t curve = 0;
    for (const gltf::MeshInstance& inst : d.meshInstances()) {
        for (const gltf::Primitive& p : d.primitives(inst.mesh)) {
            if (curve >= c.curveCount()) {
                ADD_FAILURE() << "more curves in the file than exported (" << c.curveCount() << ")";
                return worst;
            }
            const std::vector<glm::dvec3> pos = worldPositions(d, p, inst.world);
            const size_t n = c.size(curve);
            EXPECT_EQ(pos.size(), n + (c.isClosed(curve) ? 1 : 0)) << "curve " << curve;
            for (size_t i = 0; i < n && i < pos.size(); ++i)
                worst = std::max(worst, glm::length(pos[i] - c.points[c.begin(curve) + i]));
            if (c.isClosed(curve) && pos.size() == n + 1) EXPECT_EQ(pos.front(), pos.back()) << "curve " << curve;
            ++curve;
        }
    }
    EXPECT_EQ(curve, c.curveCount());
    return worst;
}

}  // namespace knit::test
