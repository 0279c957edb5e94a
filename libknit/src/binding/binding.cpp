// Binding: locate yarn vertices on the base mesh, cut yarns where they leave the UV region,
// weld ends that meet again across seams, chain the pieces into yarns (one phase per file:
// binding_locate, binding_cut, binding_weld, binding_chain), and evaluate the binding on any pose.
#include "knit/binding.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <sstream>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binding_chain.hpp"
#include "binding_gather.hpp"
#include "binding_cut.hpp"
#include "binding_evaluate_simd.hpp"
#include "binding_locate.hpp"
#include "binding_pieces.hpp"
#include "binding_weld.hpp"
#include "knit/error.hpp"
#include "knit/stitch.hpp"
#include "util/checks.hpp"
#include "util/csr.hpp"

namespace knit {
namespace {

// Refuses options and inputs binding cannot use, before anything is read.
void validateBindInput(const BaseMesh& mesh, const std::vector<glm::dvec3>& normals, const UvYarns& yarns,
                       const BindOptions& options) {
    if (!util::positiveFinite(options.yarnRadius) || !(options.clampTolerance >= 0) || !(options.weldTolerance >= 0) ||
        !util::finite(options.clampTolerance) || !util::finite(options.weldTolerance))
        throw Error(
            "the clamp tolerance and the weld tolerance must be finite and >= 0, and the yarn radius (the pattern's "
            "radius times its placement scale) positive");
    if (normals.size() != mesh.positions.size())
        throw Error("binding the yarns: " + std::to_string(normals.size()) + " vertex normals for " +
                    std::to_string(mesh.positions.size()) + " mesh vertices");
    if (!util::validOffsets(yarns.offsets, yarns.yarnCount(), yarns.vertexCount()) ||
        yarns.height.size() != yarns.vertexCount() || yarns.twist.size() != yarns.vertexCount() ||
        (!yarns.colour.empty() && yarns.colour.size() != yarns.vertexCount()) ||
        (!yarns.ghosts.empty() && yarns.ghosts.size() != yarns.yarnCount()) ||
        (!yarns.island.empty() && yarns.island.size() != yarns.yarnCount()))
        throw Error("binding the yarns: their offsets, heights, twists, colours, ghosts or islands do not match their "
                    "vertices");
}

// Every search radius is bounded by one pattern period (a grid cell): a clamp or weld tolerance
// beyond it would scan the whole mesh per vertex (hours) and clamp or weld across whole stitches.
void requireBoundedSearch(const UvGrid& grid, glm::dvec2 metresPerUv, const BindOptions& options) {
    const double period =
        std::max(grid.cellSize.x * metresPerUv.x, grid.cellSize.y * metresPerUv.y) / options.yarnRadius;
    const auto require = [&](double tolerance, const char* name) {
        if (!(tolerance > period)) return;
        std::ostringstream msg;
        msg << name << " " << tolerance << " yarn radii reaches beyond one pattern period (" << period
            << " yarn radii of " << options.yarnRadius << " m here); use at most that";
        throw Error(msg.str());
    };
    require(options.clampTolerance, "the clamp tolerance");
    if (options.weld) require(options.weldTolerance, "the weld tolerance");
}

}  // namespace

BindResult bindYarns(const BaseMesh& mesh, const std::vector<glm::dvec3>& normals, const UvGrid& grid,
                     const UvYarns& yarns, const BindOptions& options) {
    validateBindInput(mesh, normals, yarns, options);
    const impl::RestSurface rest{mesh, normals};

    // 1. Locate every yarn vertex (the clamp tolerance is in yarn radii measured in UV) and flag
    //    the steps that leave their island.
    const glm::dvec2 metresPerUv = uvToMetreScale(mesh);
    const double radiusUv = options.yarnRadius / std::max(metresPerUv.x, metresPerUv.y);
    requireBoundedSearch(grid, metresPerUv, options);
    const impl::LocatedYarns located = impl::locateYarns(mesh, grid, yarns, {options.clampTolerance * radiusUv});
    const impl::PieceVertices vertices = located.vertices(yarns);

    // 2. Cut the yarns into pieces where they leave the UV region, with a vertex on the boundary.
    const impl::CutResult cut = impl::cutYarns(mesh, grid, yarns, located);

    // 3. Weld boundary ends that meet in object space with continuing tangents.
    const double weldTol = options.weldTolerance * options.yarnRadius;
    impl::WeldResult welds;
    welds.partner.assign(2 * cut.pieces.size(), -1);
    if (options.weld && weldTol > 0)
        welds = impl::weldEnds(impl::pieceEnds(rest, cut.pieces, vertices), {weldTol, options.weldMinCos});

    // 4. Chain the pieces along the welds into yarns; a chain that returns to its start is a loop.
    impl::ChainResult chained =
        impl::chainPieces(rest, cut.pieces, vertices, welds.partner, {1e-4 * options.yarnRadius});

    BindResult result;
    result.binding = std::move(chained.binding);
    BindStats& stats = result.stats;
    stats.clampedVertices = located.clampedVertices;
    stats.cutVertices = located.outsideVertices + cut.droppedVertices;
    stats.boundaryVertices = cut.boundaryVertices;
    stats.weldedEnds = welds.weldedEnds;
    stats.openEnds = chained.openEnds;
    stats.closedLoops = chained.closedLoops;
    return result;
}

// The gather (binding_gather.hpp) over every yarn vertex, four at a time in AVX2 where the CPU
// has it (binding_evaluate_simd.cpp, bit for bit the same). The float32 evaluation is in
// binding_float.cpp.
void evaluateBinding(const Binding& binding, const std::vector<glm::uvec3>& faces,
                     const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
                     MappedYarns& out) {
    prepareMappedYarns(binding, out);
    glm::dvec3* P = out.curves.points.data();
    glm::dvec3* N = out.normals.data();
    const BindingGather gather(binding, faces, positions, normals);
    const impl::GatherArrays arrays{binding.face.data(), binding.bary.data(), binding.height.data(),
                                    faces.data(),        positions.data(),    normals.data()};
    const bool simd = impl::evaluateSimdAvailable();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, binding.vertexCount(), 16384),
                      [&](const tbb::blocked_range<size_t>& r) {
                          size_t i = simd ? impl::evaluateDoubleSimd(arrays, r.begin(), r.end(), P, N) : r.begin();
                          for (; i != r.end(); ++i) gather(i, P[i], N[i]);
                      });
}

}  // namespace knit
