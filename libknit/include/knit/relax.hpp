// knit/relax.hpp — the project's periodic yarn relaxation: a pattern's yarn comes to rest with
// its period free.
//
// Energy (in yarn radii, r = 1), minimised over every vertex and the period (px, py):
//   * inextensibility: stretch * sum_e L0_e (|e| / L0_e - 1)^2, L0 = restLength x the input's
//     edge lengths (below 1: the input is a loose construction the yarn pulls tight);
//   * bending: bend * sum_v |x_prev - 2 x_v + x_next|^2 / l^3 (l = mean rest length);
//   * contact: contact * sum (D - d)^2 over pairs of distinct, non-adjacent segments (any
//     periodic image) closer than D = contactDistance radii, d their centreline distance;
//     pairs come from a spatial hash over the periodic images (a Verlet list rebuilt when two
//     points may have come closer by half the skin, measured against the period-scaled cell).
// Solver: L-BFGS (Nocedal & Wright, Numerical Optimization, algorithm 7.4; for cells of up to
// 1000 vertices memory 20, started from the inverse of the energy's projected Hessian,
// RelaxOptions::hessianPreconditioner; else memory 8 and a scaled identity) with a
// backtracking Armijo line search, a cap on how far a vertex may move per step, and a continuous
// collision bound: no step moves two segments by more than 0.9 of their smallest distance, so
// yarns cannot pass through each other. It stops on an absolute or relative gradient tolerance,
// on the energy's decrease over a window relative to its decrease so far, or at the iteration cap.
// The pair search and the contact forces run in parallel (TBB), one slot per segment or pair,
// joined and summed in order: deterministic, the same result for any thread count.
#pragma once
#include <functional>

#include "knit/pattern.hpp"

namespace knit {

// The state of a running relaxation, for progress display (RelaxOptions::onStep).
struct RelaxStep {
    int iteration = 0;
    double energy = 0;
    Pattern pattern;  // the cell as it is now (as RelaxResult::pattern would be if it stopped here)
};
// Called every RelaxOptions::stepInterval iterations; returning false stops the relaxation
// (RelaxResult::stopped), e.g. when the user has moved on to another chart.
using RelaxStepFn = std::function<bool(const RelaxStep&)>;

struct RelaxOptions {
    double stretch = 200;           // inextensibility weight
    double bend = 1;                // bending weight
    double contact = 400;           // contact penalty weight
    double contactDistance = 2.05;  // D, in yarn radii (the penalty settles slightly inside D)
    double restLength = 1.0;        // rest length / input length, per edge
    // Optional per-vertex factor on restLength for the edge leaving that vertex (empty: 1 for
    // all): a chart's slipped and tucked loops are built stretched over two or more rows but
    // hold a plain loop's yarn (knit/chart_topology.hpp, ChartCell::restScale).
    std::vector<double> restScale;
    // Optional anchored vertices (an intarsia motif's tails, woven in behind the work and held
    // there by friction): each is drawn to where it started, carried with the period
    // (x0 px / px0, y0 py / py0, z0), by anchorWeight * squared distance in yarn radii. Free
    // tails wandered to the front of the work and opened holes; with only their ends anchored
    // they slid, and wider motifs crept on to the iteration cap (docs/charts.md, "Motifs").
    std::vector<uint32_t> anchors;
    double anchorWeight = 10;
    bool freePeriod = true;  // the period (px, py) is a variable
    // Search directions in affine period coordinates: a change of the period carries every vertex
    // with it. Most cells stop in far fewer iterations (stockinette 90 instead of 1050, the
    // intarsia and cable cells converge before the cap), but some settle in a different rest
    // state (docs/charts.md, "Relaxation"): off by default, for previews that want speed.
    bool affinePeriod = false;
    // L-BFGS preconditioned by the energy's Hessian (each term's part made positive
    // semidefinite, contact pairs near D included; a sparse LDLT factorisation every 25 steps):
    // the slow modes of a cell (the period narrowing under lace decreases, basketweave's and
    // cable4's ridges) settle in hundreds to about 2000 iterations instead of running into the
    // cap (docs/charts.md, "Relaxation"). Cells of up to 1000 vertices (about 40 stitches; above,
    // the factorisation costs more than it saves); false: plain L-BFGS (memory 8), as before.
    // Ignored with affinePeriod.
    bool hessianPreconditioner = true;
    // The first iterations stay plain L-BFGS: while a loose cell pulls tight it chooses its rest
    // state, and preconditioned from the start some cells settled in another one (garter at
    // energy 26.2 against 23.4, with a stitch that lost a crossing).
    int plainIterations = 300;
    int maxIterations = 4000;
    double gradientTolerance = 1e-4;          // stop when the largest gradient entry is below this,
    double relativeGradientTolerance = 1e-6;  // or below this times its value at the start,
    // or when the energy fell by at most relativeEnergyTolerance x (start energy - energy now)
    // over the last energyWindow iterations (0 turns this test off).
    double relativeEnergyTolerance = 1e-6;
    int energyWindow = 500;
    double maxStep = 0.25;  // largest vertex move per step, in yarn radii
    RelaxStepFn onStep;     // optional: progress and cancellation (does not change the result)
    int stepInterval = 50;  // iterations between onStep calls (>= 1)
};

struct RelaxResult {
    Pattern pattern;  // the relaxed cell (twist 0), ready for writePyp
    int iterations = 0;
    bool converged = false;  // a stop criterion was met (not the iteration cap)
    double energy = 0;
    double minDistance = 0;  // smallest distance between distinct non-adjacent segments, in radii
    // The smallest pair distance over every accepted step, in radii: above 0 means no yarn
    // passed through another (each step is also capped by the continuous collision bound).
    double closestApproach = 0;
    // Work done: energy (and gradient) evaluations, line-search ones included, and rebuilds of
    // the contact pair list.
    int evaluations = 0;
    int pairRebuilds = 0;
    bool stopped = false;  // onStep returned false: `pattern` is the state at that iteration
};

// Yarns may be closed (through the period or within the cell) or open: an open yarn (an
// intarsia motif's, with its two tails) has two free ends, which bend nothing and are held only
// by the stretch of their one segment and by contact (a tail woven in behind the work).
// Throws knit::Error when the pattern is invalid, a vertex starts or ends two edges (yarns must
// be consistently oriented paths or cycles) or a yarn has fewer than 4 vertices.
RelaxResult relaxYarn(const Pattern& initial, const RelaxOptions& options = {});

// Smallest centreline distance between distinct, non-adjacent segments (along a yarn: more
// than two segments apart), over all periodic images, in yarn radii.
double minYarnDistance(const Pattern& pattern);

}  // namespace knit
