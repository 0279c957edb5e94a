// binding_pieces.hpp (internal) — what the binding phases hand each other: bound vertices and
// pieces of yarns (runs of located vertices, cut at the UV boundary). See binding.cpp for the
// phases: locate (binding_locate), cut (binding_cut), weld (binding_weld), chain (binding_chain).
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"
#include "knit/uv_grid.hpp"

namespace knit::impl {

// One vertex of the binding: a triangle, barycentrics (b0, b1, b2), height and twist, and the
// yarn vertex whose colour it carries (itself; a boundary crossing: the vertex it leaves from).
struct BoundVertex {
    uint32_t face;
    glm::dvec3 bary;
    double height, twist;
    uint32_t origin;
};

// A maximal run of located vertices of one yarn (yarn-local indices start, start+1, ... modulo
// the yarn's size), with boundary-crossing vertices before (head) and after (tail) it.
struct Piece {
    uint32_t yarnBegin = 0, yarnSize = 0, start = 0, count = 0;
    std::optional<BoundVertex> head, tail;
    bool closed = false;
    bool boundaryEnd[2] = {false, false};  // [0] first point, [1] last point lies on a UV boundary

    size_t size() const { return count + (head ? 1 : 0) + (tail ? 1 : 0); }
};

// The located yarn vertices the pieces index into: per yarn vertex its location (not Outside
// for any vertex a piece covers), height, twist and colour (null without colours).
struct PieceVertices {
    const LocateResult* loc = nullptr;
    const double* height = nullptr;
    const double* twist = nullptr;
    const glm::vec3* colour = nullptr;
    const uint32_t* source = nullptr;  // tiled vertex id per yarn vertex (UvYarns::source); may be null

    BoundVertex vertex(size_t i) const {
        return BoundVertex{loc[i].point.face, loc[i].point.bary, height[i], twist[i], uint32_t(i)};
    }

    // Vertex k of a piece, in piece order (head, the run, tail).
    BoundVertex at(const Piece& pc, size_t k) const {
        if (pc.head) {
            if (k == 0) return *pc.head;
            --k;
        }
        if (k == pc.count) return *pc.tail;
        return vertex(pc.yarnBegin + (pc.start + k) % pc.yarnSize);
    }
    // First (last = false) or last vertex of a piece, walked forwards or reversed.
    BoundVertex end(const Piece& pc, bool last, bool reversed = false) const {
        return at(pc, last != reversed ? pc.size() - 1 : 0);
    }
};

// The rest pose the binding is computed on: the mesh and its vertex normals.
struct RestSurface {
    const BaseMesh& mesh;
    const std::vector<glm::dvec3>& normals;

    // Object-space position of a bound vertex: sum(b_i x_i) + h * normalize(sum(b_i n_i)).
    glm::dvec3 position(const BoundVertex& b) const;
};

}  // namespace knit::impl
