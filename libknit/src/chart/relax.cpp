// Periodic yarn relaxation: inextensibility, bending and contact energies minimised by L-BFGS
// over the vertices and the period (see knit/relax.hpp).
#include "knit/relax.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "lbfgs.hpp"
#include "relax_contact.hpp"

namespace knit {
namespace {

using relax::lbfgsDirection;
using relax::lbfgsRemember;
using relax::Pair;
using relax::Seg;
using Vec = Eigen::VectorXd;

// One contact pair's share: its energy and the force on its closest points (a, b their parameters).
struct PairForce {
    double energy = 0, dist = 0, a = 0, b = 0;
    glm::dvec3 gd{0.0};
};

// A segment in this evaluation: its ends (the first in tile (0, 0)), midpoint and half length.
struct SegmentNow {
    glm::dvec3 p0{0.0}, p1{0.0}, mid{0.0};
    double half = 0;
};

// The cell in yarn radii: segments, rest lengths, bending stencils and the yarn index.
struct Problem {
    size_t n = 0;
    std::vector<Seg> segs;  // ordered by their first vertex (closed yarns: segs[v] leaves v)
    std::vector<double> rest;
    double meanRest = 1;
    // The bending stencils: each vertex with a segment arriving and one leaving (every vertex
    // of a closed yarn; an open yarn's two ends bend nothing): the two segments.
    struct Bend {
        uint32_t v = 0;
        Seg in, out;  // in.a -> v (v in tile (in.dx, in.dy) of in.a), v -> out.b
    };
    std::vector<Bend> bends;
    // Anchored vertices (RelaxOptions::anchors): their starting points and the starting period.
    std::vector<glm::dvec3> anchorAt;
    double px0 = 1, py0 = 1;
    relax::YarnIndex yarns;
    RelaxOptions opt;
    mutable std::vector<PairForce> scratch;  // per-pair forces of the last evaluation
    mutable std::vector<SegmentNow> now;     // the segments of the last evaluation
    mutable int evaluations = 0;             // energy evaluations (for RelaxResult)
    bool exactDistances = false;             // pairs beyond D report their true distance too
};

glm::dvec3 vertex(const Vec& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }
void addVertex(Vec& g, size_t i, const glm::dvec3& d) {
    g[3 * i] += d.x;
    g[3 * i + 1] += d.y;
    g[3 * i + 2] += d.z;
}
// A point of tile (ox, oy): its position and the period's share of a gradient on it.
glm::dvec3 at(const Vec& v, size_t n, uint32_t i, int ox, int oy) {
    return vertex(v, i) + glm::dvec3(ox * v[3 * n], oy * v[3 * n + 1], 0);
}
void addAt(Vec& g, size_t n, uint32_t i, int ox, int oy, const glm::dvec3& d) {
    addVertex(g, i, d);
    g[3 * n] += ox * d.x;
    g[3 * n + 1] += oy * d.y;
}

double stretchEnergy(const Problem& pb, const Vec& v, Vec& g) {
    double e = 0;
    for (size_t k = 0; k < pb.segs.size(); ++k) {
        const Seg& s = pb.segs[k];
        const glm::dvec3 d = at(v, pb.n, s.b, s.dx, s.dy) - vertex(v, s.a);
        const double l = glm::length(d), strain = l / pb.rest[k] - 1;
        e += pb.opt.stretch * pb.rest[k] * strain * strain;
        const glm::dvec3 gd = (2 * pb.opt.stretch * strain / std::max(l, 1e-12)) * d;
        addAt(g, pb.n, s.b, s.dx, s.dy, gd);
        addVertex(g, s.a, -gd);
    }
    return e;
}

double bendEnergy(const Problem& pb, const Vec& v, Vec& g) {
    const double w = pb.opt.bend / (pb.meanRest * pb.meanRest * pb.meanRest);
    double e = 0;
    for (const Problem::Bend& bd : pb.bends) {
        const Seg &in = bd.in, &out = bd.out;
        const uint32_t vtx = bd.v;
        const glm::dvec3 b =
            at(v, pb.n, in.a, -in.dx, -in.dy) - 2.0 * vertex(v, vtx) + at(v, pb.n, out.b, out.dx, out.dy);
        e += w * glm::dot(b, b);
        const glm::dvec3 gb = 2 * w * b;
        addAt(g, pb.n, in.a, -in.dx, -in.dy, gb);
        addAt(g, pb.n, out.b, out.dx, out.dy, gb);
        addVertex(g, vtx, -2.0 * gb);
    }
    return e;
}

PairForce pairForce(const Problem& pb, const Pair& pr, const Vec& v) {
    const double D = pb.opt.contactDistance;
    const SegmentNow &s = pb.now[pr.s], &t = pb.now[pr.t];
    const glm::dvec3 shift(pr.ix * v[Eigen::Index(3 * pb.n)], pr.iy * v[Eigen::Index(3 * pb.n + 1)], 0);
    PairForce f;
    // Far pairs (most of the list: it reaches a skin beyond D) end on their bounding spheres, with
    // D as their distance: a lower bound, which is all the step bound needs.
    if (!pb.exactDistances) {
        const glm::dvec3 apart = s.mid - (t.mid + shift);
        const double reach = D + s.half + t.half;
        if (glm::dot(apart, apart) >= reach * reach) {
            f.dist = D;
            return f;
        }
    }
    const glm::dvec3 p0 = s.p0, p1 = s.p1, q0 = t.p0 + shift, q1 = t.p1 + shift;
    relax::closestParameters(p0, p1, q0, q1, f.a, f.b);
    const glm::dvec3 d = (p0 + f.a * (p1 - p0)) - (q0 + f.b * (q1 - q0));
    f.dist = glm::length(d);
    if (f.dist >= D) return f;
    f.energy = pb.opt.contact * (D - f.dist) * (D - f.dist);
    f.gd = (-2 * pb.opt.contact * (D - f.dist) / std::max(f.dist, 1e-12)) * d;
    return f;
}

// Anchored vertices: weight * |x - A x0|^2, A = diag(px / px0, py / py0, 1) (the start carried
// with the period).
double anchorEnergy(const Problem& pb, const Vec& v, Vec& g) {
    const Eigen::Index px = Eigen::Index(3 * pb.n), py = px + 1;
    double e = 0;
    for (size_t k = 0; k < pb.opt.anchors.size(); ++k) {
        const uint32_t i = pb.opt.anchors[k];
        const glm::dvec3 a0 = pb.anchorAt[k];
        const glm::dvec3 d = vertex(v, i) - glm::dvec3(a0.x * v[px] / pb.px0, a0.y * v[py] / pb.py0, a0.z);
        e += pb.opt.anchorWeight * glm::dot(d, d);
        const glm::dvec3 gd = 2 * pb.opt.anchorWeight * d;
        addVertex(g, i, gd);
        g[px] -= gd.x * a0.x / pb.px0;
        g[py] -= gd.y * a0.y / pb.py0;
    }
    return e;
}

// The pairs' forces are computed in parallel, each into its own slot, then summed and scattered
// in pair order: the same arithmetic as a serial loop, so the result does not depend on threads.
double contactEnergy(const Problem& pb, const std::vector<Pair>& pairs, const Vec& v, Vec& g, double* minDistance) {
    pb.now.resize(pb.segs.size());
    for (size_t k = 0; k < pb.segs.size(); ++k) {
        const Seg& sg = pb.segs[k];
        SegmentNow& sn = pb.now[k];
        sn.p0 = vertex(v, sg.a);
        sn.p1 = at(v, pb.n, sg.b, sg.dx, sg.dy);
        sn.mid = 0.5 * (sn.p0 + sn.p1);
        sn.half = 0.5 * glm::length(sn.p1 - sn.p0);
    }
    std::vector<PairForce>& forces = pb.scratch;
    forces.resize(pairs.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k != range.end(); ++k) forces[k] = pairForce(pb, pairs[k], v);
    });
    double e = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
        const PairForce& f = forces[k];
        if (minDistance) *minDistance = std::min(*minDistance, f.dist);
        if (f.dist >= pb.opt.contactDistance) continue;
        const Seg &s = pb.segs[pairs[k].s], &t = pb.segs[pairs[k].t];
        const Pair& pr = pairs[k];
        e += f.energy;
        addVertex(g, s.a, (1 - f.a) * f.gd);
        addAt(g, pb.n, s.b, s.dx, s.dy, f.a * f.gd);
        addAt(g, pb.n, t.a, pr.ix, pr.iy, -(1 - f.b) * f.gd);
        addAt(g, pb.n, t.b, t.dx + pr.ix, t.dy + pr.iy, -f.b * f.gd);
    }
    return e;
}

// The total energy and its gradient; *minDistance (when given) gets the smallest pair distance.
double energy(const Problem& pb, const std::vector<Pair>& pairs, const Vec& v, Vec& g, double* minDistance = nullptr) {
    ++pb.evaluations;
    g.setZero(v.size());
    if (minDistance) *minDistance = std::numeric_limits<double>::infinity();
    const double e = stretchEnergy(pb, v, g) + bendEnergy(pb, v, g) + contactEnergy(pb, pairs, v, g, minDistance) +
                     anchorEnergy(pb, v, g);
    if (!pb.opt.freePeriod) g[3 * pb.n] = g[3 * pb.n + 1] = 0;
    return e;
}

// ---- The Hessian preconditioner (RelaxOptions::hessianPreconditioner) ----------------------------
// L-BFGS starts each direction from H0 = (H + shift)^-1 instead of a multiple of the identity,
// H the energy's Hessian with each term's part made positive semidefinite: an edge's stretch
// keeps its along-edge stiffness and its transverse one only while stretched; bending is
// quadratic; a contact keeps its normal stiffness 2 c n n^T (dropping the negative transverse
// part), and so do pairs up to kContactMargin beyond D, which a step may bring into contact (a
// direction that ignores them runs into the contact wall and the line search backtracks). The
// remembered steps correct what the projection leaves out. The stiff terms (stretch 200,
// contact 400 against bending 1) then no longer set the step for the soft modes (the period
// narrowing under lace decreases, basketweave's ridges). Each term is a 3 x 3 matrix M on a
// combination u = sum_k c_k p_k of periodic points p_k (vertex i in tile (ox, oy): x_i + (ox px,
// oy py, 0)), so it adds c_k c_l M to the block of points k and l, the period's share included.
// Tuned on basketweave, cable4, eyelet-mesh and two lace cells (docs/charts.md, "Relaxation").
constexpr double kContactMargin = 1.0;  // radii beyond D
constexpr double kShift = 1e-3;         // H + kShift x mean diagonal (removes the free translation)
constexpr int kRefactorEvery = 25;      // steps between factorisations (H changes slowly)
constexpr size_t kPreconditionedMemory = 20;
// Larger cells keep plain L-BFGS: the factorisation's fill grows faster than the cell (a 12 x 16
// cable cell, 4608 vertices, ran for minutes of CPU instead of 12.6 s). Up to 1500: intarsia cells
// with long carries (1268 and 1336 vertices) stopped at the iteration cap under plain L-BFGS and
// converge preconditioned (docs/charts.md, "Issue 25 round 10"); no built-in is over 718.
constexpr size_t kMaxPreconditionedVertices = 1500;

struct PointRef {
    uint32_t i = 0;
    int ox = 0, oy = 0;
};

// The Hessian's entries summed in place: each entry's contributions are added in the order they
// come, as Eigen's setFromTriplets sums a list of duplicates (the same matrix to the bit, the same
// pattern: an entry exists when something was added to it), without the list (about 600 000
// triplets for a 4 x 4 cell, whose building and sorting took as long as the factorisation). The
// entries are found through their 3 x 3 block of (vertex, vertex), the period being vertex n (a
// table of (n + 1)^2 block numbers: 9 MB at the 1500 vertices the preconditioner is used up to).
class EntrySums {
public:
    struct Block {
        Eigen::Index row = 0, col = 0;  // in vertices
        std::array<double, 9> sum{};
        uint32_t touched = 0;
        // Adds to entry e (3 row + column within the block).
        void add(int e, double value) {
            sum[size_t(e)] += value;
            touched |= 1u << e;
        }
    };

    explicit EntrySums(size_t n) : points_(n + 1), blockOf_(points_ * points_, -1) {}
    // The block of rows of vertex a and columns of vertex b (n: the period), made when first used.
    size_t block(size_t a, size_t b) {
        int32_t& k = blockOf_[a * points_ + b];
        if (k < 0) {
            k = int32_t(blocks_.size());
            blocks_.push_back(Block{Eigen::Index(a), Eigen::Index(b), {}, 0});
        }
        return size_t(k);
    }
    Block& at(size_t k) { return blocks_[k]; }
    Eigen::SparseMatrix<double> matrix(Eigen::Index size) const {
        std::vector<Eigen::Triplet<double>> entries;
        entries.reserve(9 * blocks_.size());
        for (const Block& b : blocks_)
            for (int e = 0; e < 9; ++e)
                if (b.touched & (1u << e)) entries.emplace_back(3 * b.row + e / 3, 3 * b.col + e % 3, b.sum[size_t(e)]);
        Eigen::SparseMatrix<double> H(size, size);
        H.setFromTriplets(entries.begin(), entries.end());  // no duplicates left: nothing summed here
        return H;
    }

private:
    size_t points_;
    std::vector<int32_t> blockOf_;
    std::vector<Block> blocks_;
};

struct HessianBuilder {
    size_t n = 0;
    bool freePeriod = true;
    EntrySums entries;
    HessianBuilder(size_t vertices, bool period) : n(vertices), freePeriod(period), entries(vertices) {}
    // The offset of coordinate c of point p in periods (0 when the period is fixed).
    int offset(const PointRef& p, int c) const {
        if (!freePeriod) return 0;
        return c == 0 ? p.ox : c == 1 ? p.oy : 0;
    }
    // Adds c_k c_l M to the blocks of points k and l: for coordinates c1, c2 the entry of their
    // vertices, and times their offsets in periods the period's row, column and corner.
    template <size_t K>
    void add(const std::array<PointRef, K>& pts, const std::array<double, K>& coef, const Eigen::Matrix3d& M) {
        for (size_t k = 0; k < K; ++k)
            for (size_t l = 0; l < K; ++l) {
                const double cc = coef[k] * coef[l];
                if (cc == 0) continue;
                const PointRef &p = pts[k], &q = pts[l];
                const double wa[3] = {double(offset(p, 0)), double(offset(p, 1)), 0.0};
                const double wb[3] = {double(offset(q, 0)), double(offset(q, 1)), 0.0};
                const bool rowPeriod = wa[0] != 0 || wa[1] != 0, colPeriod = wb[0] != 0 || wb[1] != 0;
                // The blocks first (made when new), then their addresses (the list no longer grows).
                const size_t kvv = entries.block(p.i, q.i), kvp = colPeriod ? entries.block(p.i, n) : kvv,
                             kpv = rowPeriod ? entries.block(n, q.i) : kvv,
                             kpp = rowPeriod && colPeriod ? entries.block(n, n) : kvv;
                EntrySums::Block &vv = entries.at(kvv), &vp = entries.at(kvp), &pv = entries.at(kpv),
                                 &pp = entries.at(kpp);
                for (int c1 = 0; c1 < 3; ++c1)
                    for (int c2 = 0; c2 < 3; ++c2) {
                        const double m = cc * M(c1, c2);
                        if (m == 0) continue;
                        const int e = 3 * c1 + c2;
                        vv.add(e, m);
                        if (wb[c2] != 0) vp.add(e, m * wb[c2]);
                        if (wa[c1] != 0) pv.add(e, m * wa[c1]);
                        if (wa[c1] != 0 && wb[c2] != 0) pp.add(e, m * wa[c1] * wb[c2]);
                    }
            }
    }
    // A diagonal entry of its own (the fixed period's).
    void addDiagonal(Eigen::Index i, double value) {
        entries.at(entries.block(size_t(i / 3), size_t(i / 3))).add(int(i % 3) * 4, value);
    }
};

Eigen::Matrix3d outer(const glm::dvec3& a) {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = a[r] * a[c];
    return m;
}

// The projected Hessian at v; the contact part from the pairs of the last evaluation at v
// (Problem::scratch, their closest-point parameters).
Eigen::SparseMatrix<double> hessian(const Problem& pb, const std::vector<Pair>& pairs, const Vec& v) {
    HessianBuilder h(pb.n, pb.opt.freePeriod);
    for (size_t k = 0; k < pb.segs.size(); ++k) {
        const Seg& s = pb.segs[k];
        const glm::dvec3 d = at(v, pb.n, s.b, s.dx, s.dy) - vertex(v, s.a);
        const double l = std::max(glm::length(d), 1e-12), L0 = pb.rest[k];
        const glm::dvec3 t = d / l;
        const Eigen::Matrix3d tt = outer(t);
        const double transverse = std::max(0.0, 1 - L0 / l);
        const Eigen::Matrix3d M = (2 * pb.opt.stretch / L0) * (tt + transverse * (Eigen::Matrix3d::Identity() - tt));
        h.add<2>({PointRef{s.a, 0, 0}, PointRef{s.b, s.dx, s.dy}}, {-1.0, 1.0}, M);
    }
    const double w = pb.opt.bend / (pb.meanRest * pb.meanRest * pb.meanRest);
    for (const Problem::Bend& bd : pb.bends) {
        const Seg &in = bd.in, &out = bd.out;
        h.add<3>({PointRef{in.a, -in.dx, -in.dy}, PointRef{bd.v, 0, 0}, PointRef{out.b, out.dx, out.dy}},
                 {1.0, -2.0, 1.0}, 2 * w * Eigen::Matrix3d::Identity());
    }
    for (size_t k = 0; k < pairs.size(); ++k) {
        const PairForce& f = pb.scratch[k];
        // Pairs in contact, and pairs up to kContactMargin beyond D (their exact distance is
        // known; D exactly is a far pair's bound), which a step may bring into contact.
        if (f.dist >= pb.opt.contactDistance + kContactMargin || f.dist == pb.opt.contactDistance) continue;
        const Pair& pr = pairs[k];
        const Seg &s = pb.segs[pr.s], &t = pb.segs[pr.t];
        const glm::dvec3 shift(pr.ix * v[Eigen::Index(3 * pb.n)], pr.iy * v[Eigen::Index(3 * pb.n + 1)], 0);
        const SegmentNow &sn = pb.now[pr.s], &tn = pb.now[pr.t];
        const glm::dvec3 dv = (sn.p0 + f.a * (sn.p1 - sn.p0)) - (tn.p0 + shift + f.b * (tn.p1 - tn.p0));
        const glm::dvec3 n = dv / std::max(glm::length(dv), 1e-300);
        h.add<4>({PointRef{s.a, 0, 0}, PointRef{s.b, s.dx, s.dy}, PointRef{t.a, pr.ix, pr.iy},
                  PointRef{t.b, t.dx + pr.ix, t.dy + pr.iy}},
                 {1 - f.a, f.a, -(1 - f.b), -f.b}, 2 * pb.opt.contact * outer(n));
    }
    for (const uint32_t i : pb.opt.anchors)  // the vertex's part (the period's is left out)
        h.add<1>({PointRef{i, 0, 0}}, {1.0}, 2 * pb.opt.anchorWeight * Eigen::Matrix3d::Identity());
    const Eigen::Index size = v.size();
    if (!pb.opt.freePeriod)
        for (Eigen::Index i = size - 2; i < size; ++i) h.addDiagonal(i, 1.0);
    return h.entries.matrix(size);
}

// Factorises H + shift s I, s the mean diagonal of H (the shift also removes the cell's free
// translation), raising the shift tenfold until the factorisation is positive definite. Returns
// false when it never is (the step is then plain L-BFGS).
using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;
bool factorise(const Eigen::SparseMatrix<double>& H, Factor& ldlt) {
    const double scale = std::max(H.diagonal().mean(), 1e-12);
    for (int attempt = 0; attempt < 8; ++attempt) {
        const double lambda = kShift * std::pow(10.0, attempt);
        Eigen::SparseMatrix<double> A = H;
        for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += lambda * scale;
        ldlt.compute(A);
        if (ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0) return true;
    }
    return false;
}

// Step 1: the problem in yarn radii, segments ordered by their first vertex.
Problem setUp(const Pattern& p, const RelaxOptions& opt, Vec& v) {
    validatePattern(p, p.name);
    Problem pb;
    pb.opt = opt;
    pb.n = p.points.size();
    std::vector<int32_t> out(pb.n, -1), in(pb.n, -1);
    for (size_t k = 0; k < p.edges.size(); ++k) {
        const PeriodicEdge& e = p.edges[k];
        if (out[e.v0] >= 0 || in[e.v1] >= 0)
            throw Error(p.name + ": relaxation needs yarns with consistently oriented edges (vertex " +
                        std::to_string(out[e.v0] >= 0 ? e.v0 : e.v1) + ")");
        out[e.v0] = int32_t(k);
        in[e.v1] = int32_t(k);
    }
    for (size_t i = 0; i < pb.n; ++i)
        if (out[i] >= 0) {
            const PeriodicEdge& e = p.edges[size_t(out[i])];
            pb.segs.push_back({e.v0, e.v1, e.dx, e.dy});
            out[i] = int32_t(pb.segs.size() - 1);
        }
    for (const Seg& s : pb.segs) in[s.b] = out[s.a];
    for (size_t i = 0; i < pb.n; ++i)
        if (in[i] >= 0 && out[i] >= 0)
            pb.bends.push_back({uint32_t(i), pb.segs[size_t(in[i])], pb.segs[size_t(out[i])]});
    if (!(opt.restLength > 0) || !(opt.contactDistance > 0) || opt.maxIterations < 0 || opt.plainIterations < 0)
        throw Error(
            "yarn relaxation: the rest length and the contact distance must be positive and the iteration counts >= 0");
    if (!(opt.relativeGradientTolerance >= 0) || !(opt.relativeEnergyTolerance >= 0) || opt.energyWindow < 0)
        throw Error("yarn relaxation: the relative gradient and energy tolerances and the energy window must be >= 0");
    if (!opt.restScale.empty() && opt.restScale.size() != pb.n)
        throw Error("yarn relaxation: the rest-length scale has " + std::to_string(opt.restScale.size()) +
                    " entries for " + std::to_string(pb.n) + " vertices");
    for (const double f : opt.restScale)
        if (!(f > 0) || !std::isfinite(f)) throw Error("yarn relaxation: the rest-length scales must be positive");
    pb.yarns = relax::indexYarns(p, pb.segs, true);
    for (int32_t len : pb.yarns.length)
        if (len < 4) throw Error(p.name + ": relaxation needs yarns of at least 4 vertices");
    v.resize(Eigen::Index(3 * pb.n + 2));
    for (size_t i = 0; i < pb.n; ++i)
        for (int c = 0; c < 3; ++c) v[Eigen::Index(3 * i + size_t(c))] = p.points[i][c] / p.radius;
    v[Eigen::Index(3 * pb.n)] = p.px / p.radius;
    v[Eigen::Index(3 * pb.n + 1)] = p.py / p.radius;
    if (!(opt.anchorWeight >= 0) || !std::isfinite(opt.anchorWeight))
        throw Error("yarn relaxation: the anchor weight must be >= 0");
    pb.px0 = p.px / p.radius;
    pb.py0 = p.py / p.radius;
    for (const uint32_t i : opt.anchors) {
        if (i >= pb.n)
            throw Error("yarn relaxation: anchored vertex " + std::to_string(i) + " of " + std::to_string(pb.n));
        pb.anchorAt.push_back(vertex(v, i));
    }
    double total = 0;
    for (const Seg& s : pb.segs) {
        const double scale = opt.restScale.empty() ? 1.0 : opt.restScale[s.a];
        pb.rest.push_back(opt.restLength * scale * glm::length(at(v, pb.n, s.b, s.dx, s.dy) - vertex(v, s.a)));
        total += pb.rest.back();
    }
    pb.meanRest = total / double(std::max<size_t>(pb.segs.size(), 1));
    return pb;
}

std::vector<glm::dvec3> positions(const Problem& pb, const Vec& v) {
    std::vector<glm::dvec3> x(pb.n);
    for (size_t i = 0; i < pb.n; ++i) x[i] = vertex(v, i);
    return x;
}

std::vector<Pair> pairsOf(const Problem& pb, const Vec& v, double skin) {
    return relax::findPairs(positions(pb, v), v[Eigen::Index(3 * pb.n)], v[Eigen::Index(3 * pb.n + 1)], pb.segs,
                            pb.yarns, pb.opt.contactDistance + skin);
}

// The largest vertex move of a step (the period counts as moving the far copies).
double largestMove(const Problem& pb, const Vec& d) {
    double m = 0;
    for (size_t i = 0; i < pb.n; ++i) m = std::max(m, glm::length(vertex(d, i)));
    return std::max({m, std::abs(d[Eigen::Index(3 * pb.n)]), std::abs(d[Eigen::Index(3 * pb.n + 1)])});
}

// How much closer two points of the cell can have come since the pair list was built at `built`,
// for points that were farther apart than `cutoff` then. The period scales the cell by A =
// diag(sx, sy, 1) (every periodic image with it) and each vertex moved by at most m away from
// where A takes it: two points d0 > cutoff apart are now at least min(sx, sy, 1) d0 - 2 m apart.
// Measured against the scaled cell, a cell that only shrinks or grows (the period settling)
// does not force rebuilds.
double driftSince(const Problem& pb, const Vec& built, const Vec& v, double cutoff) {
    const Eigen::Index px = Eigen::Index(3 * pb.n), py = px + 1;
    const glm::dvec3 scale(v[px] / built[px], v[py] / built[py], 1.0);
    double m = 0;
    for (size_t i = 0; i < pb.n; ++i) m = std::max(m, glm::length(vertex(v, i) - scale * vertex(built, i)));
    return 2 * m + cutoff * std::max(0.0, 1.0 - std::min(scale.x, scale.y));
}

// Continuous collision bound: with M = largestMove, a point of a segment moves by at most 3 M in
// a step (its vertices, plus the period up to twice for an image's end), a point of the other
// segment of a pair by at most 5 M (its image offset adds up to two periods more), so two
// segments dmin apart cannot meet while 8 M stays below dmin. Pairs outside the list were
// farther apart than the cutoff (D + skin) when it was built and came closer by at most the
// drift since, so dmin counts as at most cutoff - drift.
double collisionFreeStep(const Problem& pb, const Vec& d, double dmin, double cutoff) {
    return 0.9 * std::min(dmin, cutoff) / std::max(8.0 * largestMove(pb, d), 1e-300);
}

// Affine period coordinates (RelaxOptions::affinePeriod): in them a change of the period carries
// every vertex with it (x -> A x, A = diag(px'/px, py'/py, 1)), so the cell shrinking or growing
// as a whole is one variable instead of a slow drift of every vertex, which L-BFGS followed over
// thousands of iterations. T is the map from a step in these coordinates to a step of v, at v;
// the search direction is found in them and applied as T dw.
Vec affineStep(const Problem& pb, const Vec& v, const Vec& dw) {  // T dw
    const Eigen::Index px = Eigen::Index(3 * pb.n), py = px + 1;
    Vec d = dw;
    for (Eigen::Index i = 0; i < px; i += 3) {
        d[i] += v[i] * dw[px] / v[px];
        d[i + 1] += v[i + 1] * dw[py] / v[py];
    }
    return d;
}
Vec affineGradient(const Problem& pb, const Vec& v, const Vec& g) {  // T^T g
    const Eigen::Index px = Eigen::Index(3 * pb.n), py = px + 1;
    Vec gw = g;
    for (Eigen::Index i = 0; i < px; i += 3) {
        gw[px] += g[i] * v[i] / v[px];
        gw[py] += g[i + 1] * v[i + 1] / v[py];
    }
    return gw;
}
Vec affineInverse(const Problem& pb, const Vec& v, const Vec& dv) {  // T^-1 dv
    const Eigen::Index px = Eigen::Index(3 * pb.n), py = px + 1;
    Vec dw = dv;
    for (Eigen::Index i = 0; i < px; i += 3) {
        dw[i] -= v[i] * dv[px] / v[px];
        dw[i + 1] -= v[i + 1] * dv[py] / v[py];
    }
    return dw;
}

// Stop: the largest gradient entry is below the absolute tolerance or below the relative one
// times its value at the start, or the energy fell by less than relativeEnergyTolerance times
// the whole decrease so far over the last energyWindow iterations (the stretched, slowly sliding
// yarn of a large cell otherwise creeps on to the iteration cap).
bool converged(const RelaxOptions& o, const Vec& g, double gStart, double eStart, const std::vector<double>& history) {
    const double gNow = g.lpNorm<Eigen::Infinity>();
    if (gNow < o.gradientTolerance || gNow <= o.relativeGradientTolerance * gStart) return true;
    const size_t w = size_t(std::max(o.energyWindow, 1));
    if (history.size() <= w) return false;
    const double eNow = history.back(), eThen = history[history.size() - 1 - w];
    return eThen - eNow <= o.relativeEnergyTolerance * (eStart - eNow);
}

Pattern toPattern(const Pattern& initial, const Problem& pb, const Vec& v) {
    Pattern out = initial;
    const double r = initial.radius;
    for (size_t i = 0; i < pb.n; ++i) out.points[i] = vertex(v, i) * r;
    out.px = v[Eigen::Index(3 * pb.n)] * r;
    out.py = v[Eigen::Index(3 * pb.n + 1)] * r;
    out.twist.assign(pb.n, 0.0);
    out.extraBlocks.clear();
    return out;
}

}  // namespace

RelaxResult relaxYarn(const Pattern& initial, const RelaxOptions& options) {
    Vec v;
    const Problem pb = setUp(initial, options, v);
    const double skin = 1.0;
    std::vector<Pair> pairs = pairsOf(pb, v, skin);
    Vec built = v;     // the state the pair list was built at
    double drift = 0;  // driftSince(built)
    Vec g, gNew, vNew;
    double dmin = 0, dminNew = 0;  // smallest pair distance now and after the trial step
    double e = energy(pb, pairs, v, g, &dmin);
    const double gStart = g.lpNorm<Eigen::Infinity>(), eStart = e;  // the stop tests' references
    std::vector<Vec> S, Y;
    Factor ldlt;
    bool haveFactor = false;  // ldlt holds the preconditioner (refactorised every kRefactorEvery steps)
    RelaxResult result;
    result.closestApproach = dmin;
    std::vector<double> history;  // energy after each iteration
    int it = 0;
    for (; it < options.maxIterations; ++it) {
        if (converged(options, g, gStart, eStart, history)) {
            result.converged = true;
            break;
        }
        if (options.onStep && it > 0 && it % std::max(options.stepInterval, 1) == 0 &&
            !options.onStep(RelaxStep{it, e, toPattern(initial, pb, v)})) {
            result.stopped = true;
            break;
        }
        // Step 2: direction (L-BFGS, preconditioned by the Hessian when asked, steepest descent
        // when it is not a descent direction), in affine period coordinates when asked.
        const bool affine = options.affinePeriod && options.freePeriod;
        const bool preconditioned = options.hessianPreconditioner && !affine && pb.n <= kMaxPreconditionedVertices &&
                                    it >= options.plainIterations;
        const Vec gw = affine ? affineGradient(pb, v, g) : g;
        Vec dw;
        if (preconditioned && (it % kRefactorEvery == 0 || !haveFactor))
            haveFactor = factorise(hessian(pb, pairs, v), ldlt);
        if (preconditioned && haveFactor)
            dw = lbfgsDirection(gw, S, Y, [&ldlt](const Vec& q) -> Vec { return ldlt.solve(q); });
        else dw = lbfgsDirection(gw, S, Y);
        if (dw.dot(gw) >= 0) {
            S.clear();
            Y.clear();
            dw = -gw;
        }
        const Vec d = affine ? affineStep(pb, v, dw) : dw;
        // Step 3: backtracking line search from a step capped at maxStep per vertex and by the
        // continuous collision bound (no two segments can pass through each other).
        double step = std::min({1.0, options.maxStep / std::max(largestMove(pb, d), 1e-300),
                                collisionFreeStep(pb, d, dmin, options.contactDistance + skin - drift)});
        double eNew = e;
        bool accepted = false;
        for (int k = 0; k < 40 && !accepted; ++k) {
            if (k > 0) step *= 0.5;
            vNew = v + step * d;
            eNew = energy(pb, pairs, vNew, gNew, &dminNew);
            accepted = eNew <= e + 1e-4 * step * d.dot(g);
        }
        if (!accepted) {
            if (S.empty()) break;  // no descent even along -g: at a minimum to round-off
            S.clear();
            Y.clear();
            if (preconditioned) {
                e = energy(pb, pairs, v, g, &dmin);  // Problem::scratch at v again, for the Hessian
                haveFactor = false;
            }
            continue;
        }
        // Step 4: memory update; the pair list is rebuilt when two points may have come closer by
        // half the skin since it was built.
        if (affine) lbfgsRemember(S, Y, affineInverse(pb, v, vNew - v), affineGradient(pb, v, gNew) - gw);
        else lbfgsRemember(S, Y, vNew - v, gNew - g, preconditioned ? kPreconditionedMemory : 8);
        v.swap(vNew);
        g.swap(gNew);
        e = eNew;
        history.push_back(e);
        dmin = dminNew;
        result.closestApproach = std::min(result.closestApproach, dmin);
        drift = driftSince(pb, built, v, options.contactDistance + skin);
        if (drift > 0.5 * skin) {
            pairs = pairsOf(pb, v, skin);
            ++result.pairRebuilds;
            built = v;
            drift = 0;
            e = energy(pb, pairs, v, g, &dmin);
        }
    }
    result.iterations = it;
    result.evaluations = pb.evaluations;
    result.energy = e;
    result.pattern = toPattern(initial, pb, v);
    result.minDistance = minYarnDistance(result.pattern);
    return result;
}

double minYarnDistance(const Pattern& pattern) {
    Vec v;
    Problem pb = setUp(pattern, RelaxOptions{}, v);
    pb.exactDistances = true;
    const std::vector<Pair> pairs = pairsOf(pb, v, 6.0);
    double m = std::numeric_limits<double>::infinity();
    Vec g;
    g.setZero(v.size());
    contactEnergy(pb, pairs, v, g, &m);
    return m;
}

}  // namespace knit
