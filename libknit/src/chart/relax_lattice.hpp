// relax_lattice.hpp (internal) — a pattern's periodic cell relaxed on a prescribed, deformed
// lattice: the strain tables' yarn-level solver (deform/strain_table.cpp).
//
// The unknowns are the cell's vertices in reference (pattern) space, Y; the yarn lives at
// M Y, M = [F 0; 0 1] (F the 2 x 2 in-plane map, heights unchanged), and its periodic images at
// M (Y + (i px, j py, 0)). The energy is chart relaxation's (knit/relax.hpp), evaluated on the
// deformed yarn, with the period fixed: inextensibility against the rest pattern's own edge
// lengths (weighted far above bending), bending, and the contact penalty between segments of any
// image. L-BFGS with a backtracking line search; every step is capped so that no two segments
// move by more than 0.9 of their distance (the crossing structure is kept: yarns never pass
// through each other). Kept apart from relax.cpp so that the chart solver stays as it is.
#pragma once
#include <memory>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec3.hpp>

#include "knit/pattern.hpp"

namespace knit::impl {

struct LatticeRelaxOptions {
    double stretch = 2000;          // inextensibility weight
    double bend = 1;                // bending weight
    double contact = 400;           // contact penalty weight
    double contactDistance = 2.05;  // in yarn radii
    double barrier = 2000;          // weight of the contact barrier (see contactTerm)
    double barrierDistance = 1.25;  // where the barrier starts, in yarn radii
    int maxIterations = 600;
    double gradientTolerance = 1e-3;  // largest gradient entry, in the energy's units per radius
    double maxStep = 0.25;            // largest vertex move per step, in yarn radii
    // Rest lengths as a fraction of the pattern's own edge lengths: below 1 the yarn is under
    // tension everywhere and pulls itself taut against the contacts (the shortest yarn a lattice
    // allows, tools/strain_bound.cpp); the strain tables use 1.
    double restLengthScale = 1;
    // Contact pairs whose distance, less twice the largest vertex move since the pair list was
    // built, is still at least the contact distance are not measured (they add nothing): the same
    // result to the bit, about a quarter less CPU on a 400-vertex cell. Off only to check that.
    bool skipPairsSurelyApart = true;
    // How the Newton steps are solved: by the cell's size (denseNewton), or forced either way (to
    // compare them).
    enum class Newton { BySize, Dense, Sparse };
    Newton newton = Newton::BySize;
};

struct LatticeRelaxResult {
    std::vector<glm::dvec3> points;  // reference-space vertices (metres, the pattern's units)
    int iterations = 0;
    int stages = 0;  // lattice stages relaxed (latticeStages)
    bool converged = false;
    double energy = 0;
    double minDistance = 0;    // closest distinct non-adjacent segments of the deformed yarn, in radii
    size_t pairsMeasured = 0;  // closest points of contact pairs found (the contact terms' work)
};

// The cell of one pattern, set up once (rest lengths from the pattern's own edges) and relaxed
// under any number of lattice maps. Throws knit::Error for a pattern relaxation cannot use (open
// yarns, inconsistently oriented edges, yarns under 4 vertices) or invalid options.
class LatticeCell {
public:
    LatticeCell(const Pattern& pattern, const LatticeRelaxOptions& options);
    ~LatticeCell();
    LatticeCell(const LatticeCell&) = delete;
    LatticeCell& operator=(const LatticeCell&) = delete;

    // Relaxes from `start` (reference-space vertices in metres, at rest on `startLattice`; empty:
    // the pattern's own, on the undeformed lattice) on the lattice deformed by F (columns: where
    // the pattern's x and y axes go), moving the lattice there in stages. Thread-safe: each call
    // has its own state.
    LatticeRelaxResult relax(const glm::dmat2& F, const std::vector<glm::dvec3>& start,
                             const glm::dmat2& startLattice = glm::dmat2(1.0)) const;

    size_t vertexCount() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// The lattice stages LatticeCell::relax moves the lattice through from `start` to F: each changes
// the map by at most a tenth of its smallest singular value (and of 1), so that it brings no two
// points closer than 90 % of their distance.
int latticeStages(const glm::dmat2& F, const glm::dmat2& start);

// Whether a cell of n vertices solves its Newton steps by a dense Cholesky factorisation (else by
// conjugate gradients on a kept sparse factor, block_hessian.hpp). Up to 64: the stockinette's 24
// (its tables byte for byte as before); the 3n x 3n factorisation of a 192-vertex cell made its
// table 5 x slower than the sparse path (docs/deformation.md "Cells of 100-200 vertices").
inline bool denseNewton(size_t n) { return n <= 64; }

// The pattern's cell at rest on its own (undeformed) lattice under the default options, relaxed
// with 8 x the iteration cap and a thousandth of the gradient tolerance: the rest cell every strain table measures against (the built-in
// stockinette is made this way, so that zero strain moves nothing). Reference-space vertices in
// metres.
std::vector<glm::dvec3> restCell(const Pattern& pattern, const LatticeRelaxOptions& options = {});

// Total yarn length of the pattern's cell with reference-space vertices `points` (metres) on the
// lattice deformed by F (heights unchanged): the polyline through the cell's edges.
double cellYarnLength(const Pattern& pattern, const std::vector<glm::dvec3>& points, const glm::dmat2& F);

}  // namespace knit::impl
