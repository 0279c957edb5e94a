// Tiny inputs for the binding phase tests (binding_*_test.cpp), built in code: UV yarns from
// point lists, the UV grid of a small mesh, flat vertex normals, hand-made vertex locations.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "binding/binding_pieces.hpp"
#include "hard/hard_cases.hpp"
#include "knit/base_mesh.hpp"
#include "knit/stitch.hpp"
#include "knit/uv_grid.hpp"

namespace knit::test {

// One yarn per point list; heights are 0.001 per vertex index within the yarn, twists 0.
inline UvYarns uvYarns(const std::vector<std::vector<glm::dvec2>>& yarns, const std::vector<uint8_t>& closed) {
    UvYarns out;
    for (const std::vector<glm::dvec2>& yarn : yarns) {
        for (size_t k = 0; k < yarn.size(); ++k) {
            out.uv.push_back(yarn[k]);
            out.height.push_back(0.001 * double(k));
            out.twist.push_back(0.0);
        }
        out.offsets.push_back(uint32_t(out.uv.size()));
    }
    out.closed = closed;
    return out;
}

// The UV grid of a mesh with quarter-unit cells.
inline UvGrid quarterGrid(const BaseMesh& mesh) {
    UvGridOptions o;
    o.cellSize = glm::dvec2(0.25);
    return buildUvGrid(mesh, o);
}

// A flat mesh's vertex normals: +z everywhere.
inline std::vector<glm::dvec3> upNormals(const BaseMesh& mesh) {
    return std::vector<glm::dvec3>(mesh.positions.size(), {0, 0, 1});
}

// A vertex located (Inside) at the given triangle and barycentrics.
inline LocateResult locatedAt(uint32_t face, glm::dvec3 bary) {
    LocateResult r;
    r.status = LocateStatus::Inside;
    r.point.face = face;
    r.point.bary = bary;
    return r;
}

// Unit square in UV, `size` metres wide in 3D (z = 0), n x n quads (hard::flatSquare).
inline BaseMesh unitSquare(int n = 4, double size = 1.0) { return hard::flatSquare(n, size); }

// Two unit-square islands side by side in UV ([0,1] and [1,2] along u), each with its own UV
// vertices (so two islands, meeting along u = 1) and one shared 3D surface (x = u).
inline BaseMesh twoChartsSideBySide() {
    BaseMesh m = unitSquare(2);
    BaseMesh right = unitSquare(2);
    for (glm::dvec2& uv : right.uvs) uv.x += 1.0;
    for (glm::dvec3& p : right.positions) p.x += 1.0;
    hard::append(m, right);
    hard::weldPositions(m);
    return m;
}

}  // namespace knit::test
