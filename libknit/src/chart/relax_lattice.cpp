// A periodic cell relaxed on a prescribed, deformed lattice (see relax_lattice.hpp): the energy of
// chart relaxation on the yarn M Y, minimised over the reference-space vertices Y.
#include "relax_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "knit/error.hpp"
#include "block_hessian.hpp"
#include "relax_contact.hpp"

namespace knit::impl {

using relax::Pair;
using relax::Seg;
using Vec = Eigen::VectorXd;

struct LatticeCell::Impl {
    size_t n = 0;
    double radius = 1, px = 1, py = 1;  // px, py in radii
    std::vector<Seg> segs;              // indexed by their first vertex
    std::vector<Seg> before;            // per vertex: the segment arriving at it
    std::vector<double> rest;           // rest lengths (radii)
    double meanRest = 1;
    relax::YarnIndex yarns;
    std::vector<glm::dvec3> start;  // the pattern's vertices in radii
    LatticeRelaxOptions opt;
};

namespace {

using Impl = LatticeCell::Impl;

// The contact energy of two segments whose centrelines are `dist` apart (radii), with its first
// and second derivatives: the penalty o.contact (D - dist)^2 below the contact distance D, plus a
// barrier below o.barrierDistance (IPC's, -kappa (dist - d^)^2 ln(dist / d^), which grows without
// bound as the yarns' centrelines meet): the yarn's cross-section gives way under load, but not
// to nothing, however hard the yarn is pulled.
struct ContactTerm {
    double e = 0, de = 0, d2e = 0;
};
ContactTerm contactTerm(const LatticeRelaxOptions& o, double dist) {
    ContactTerm t;
    const double D = o.contactDistance;
    if (dist < D) {
        t.e = o.contact * (D - dist) * (D - dist);
        t.de = -2 * o.contact * (D - dist);
        t.d2e = 2 * o.contact;
    }
    const double h = o.barrierDistance, k = o.barrier;
    if (dist < h && k > 0) {
        if (!(dist > 1e-12)) {
            t.e = std::numeric_limits<double>::infinity();
            return t;
        }
        const double r = dist - h, lg = std::log(dist / h);
        t.e += -k * r * r * lg;
        t.de += -k * (2 * r * lg + r * r / dist);
        t.d2e += -k * (2 * lg + 4 * r / dist - r * r / (dist * dist));
    }
    return t;
}

// One relaxation: the map, the lattice and the contact pairs.
struct State {
    const Impl& c;
    glm::dmat3 M{1.0};
    glm::dvec3 a1{0.0}, a2{0.0};  // deformed lattice vectors (radii)
    double sigmaMin = 1;          // smallest singular value of F
    std::vector<Pair> pairs;
    std::vector<double> builtDistance;  // per pair: its distance when the list was built
    std::vector<glm::dvec3> built;      // the deformed vertices when the list was built
    std::vector<glm::dvec3> x;          // deformed vertices (radii), of the last evaluation
    int evaluations = 0;
    mutable size_t measured = 0;  // closest() calls

    explicit State(const Impl& cell) : c(cell) {}

    glm::dvec3 shift(int ix, int iy) const { return double(ix) * a1 + double(iy) * a2; }
    glm::dvec3 segEnd(const Seg& s) const { return x[s.b] + shift(s.dx, s.dy); }

    void deform(const Vec& v) {
        x.resize(c.n);
        for (size_t i = 0; i < c.n; ++i)
            x[i] = M * glm::dvec3(v[Eigen::Index(3 * i)], v[Eigen::Index(3 * i + 1)], v[Eigen::Index(3 * i + 2)]);
    }

    // Every pair of distinct, non-adjacent segments (any image) whose deformed centrelines are
    // closer than `cutoff`: all images within reach, tested directly (cells are small).
    void findPairs(const Vec& v, double cutoff) {
        pairs.clear();
        builtDistance.clear();
        built = x;
        double reach = 0;  // longest deformed segment
        for (const Seg& s : c.segs) reach = std::max(reach, glm::length(segEnd(s) - x[s.a]));
        const double refCut = (cutoff + 2 * reach) / sigmaMin;
        double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        double hi[2] = {-lo[0], -lo[1]};
        for (size_t i = 0; i < c.n; ++i)
            for (int k = 0; k < 2; ++k) {
                lo[k] = std::min(lo[k], v[Eigen::Index(3 * i + size_t(k))]);
                hi[k] = std::max(hi[k], v[Eigen::Index(3 * i + size_t(k))]);
            }
        const double extentX = hi[0] - lo[0], extentY = hi[1] - lo[1];
        const int kx = int(std::ceil((refCut + extentX) / c.px)) + 1,
                  ky = int(std::ceil((refCut + extentY) / c.py)) + 1;
        // Bounding spheres first (midpoint and half length): most images are far.
        std::vector<glm::dvec3> mid(c.n);
        std::vector<double> half(c.n);
        for (size_t k = 0; k < c.n; ++k) {
            mid[k] = 0.5 * (x[c.segs[k].a] + segEnd(c.segs[k]));
            half[k] = 0.5 * glm::length(segEnd(c.segs[k]) - x[c.segs[k].a]);
        }
        // Per segment pair only the images whose lattice shift can bring the spheres within reach:
        // the shift ix a1 + iy a2 within reachPair of mid[s] - mid[t] in the plane, i.e. (ix, iy)
        // within reachPair times the rows' norms of the inverse lattice of its lattice coordinates.
        const double det = a1.x * a2.y - a2.x * a1.y;
        const glm::dvec2 row1 = glm::dvec2(a2.y, -a2.x) / det, row2 = glm::dvec2(-a1.y, a1.x) / det;
        const double n1 = glm::length(row1), n2 = glm::length(row2);
        for (uint32_t s = 0; s < c.n; ++s)
            for (uint32_t t = s; t < c.n; ++t) {
                const double reachPair = cutoff + half[s] + half[t];
                const double dz = mid[t].z - mid[s].z;
                if (dz * dz >= reachPair * reachPair) continue;  // no image is within reach
                const glm::dvec2 w(mid[s].x - mid[t].x, mid[s].y - mid[t].y);
                const double u1 = glm::dot(row1, w), u2 = glm::dot(row2, w);
                const double r1 = reachPair * n1 * (1 + 1e-9) + 1e-9, r2 = reachPair * n2 * (1 + 1e-9) + 1e-9;
                const int x0 = std::max(-kx, int(std::floor(u1 - r1))), x1 = std::min(kx, int(std::ceil(u1 + r1)));
                const int y0 = std::max(-ky, int(std::floor(u2 - r2))), y1 = std::min(ky, int(std::ceil(u2 + r2)));
                for (int iy = y0; iy <= y1; ++iy)
                    for (int ix = x0; ix <= x1; ++ix) {
                        if (t == s && (iy < 0 || (iy == 0 && ix <= 0))) continue;
                        const glm::dvec3 apart = mid[t] + shift(ix, iy) - mid[s];
                        if (glm::dot(apart, apart) >= reachPair * reachPair) continue;
                        const Pair pr{s, t, ix, iy};
                        if (relax::nearAlongYarn(c.yarns, c.segs, pr, 3)) continue;
                        const double dist = distance(pr);
                        if (dist < cutoff) {
                            pairs.push_back(pr);
                            builtDistance.push_back(dist);
                        }
                    }
            }
    }

    // The closest points of a listed pair's segments: their parameters a (on pr.s) and b (on pr.t),
    // the vector between them and its length.
    struct Closest {
        double a = 0, b = 0;
        glm::dvec3 d{0.0};
        double dist = 0;
    };
    Closest closest(const Pair& pr) const {
        const Seg &s = c.segs[pr.s], &t = c.segs[pr.t];
        const glm::dvec3 p0 = x[s.a], p1 = segEnd(s), q0 = x[t.a] + shift(pr.ix, pr.iy),
                         q1 = segEnd(t) + shift(pr.ix, pr.iy);
        Closest k;
        ++measured;
        relax::closestParameters(p0, p1, q0, q1, k.a, k.b);
        k.d = (p0 + k.a * (p1 - p0)) - (q0 + k.b * (q1 - q0));
        k.dist = glm::length(k.d);
        return k;
    }

    double distance(const Pair& pr) const { return closest(pr).dist; }

    // Twice the largest move of a vertex since the list was built: no two points of two segments
    // have come closer by more (the lattice is fixed while a list lives).
    double slack() const {
        double m = 0;
        for (size_t i = 0; i < c.n; ++i) m = std::max(m, glm::length(x[i] - built[i]));
        return 2 * m;
    }
    // The lower bound a pair's distance has now (builtDistance - slack, less a rounding margin);
    // a pair whose bound is at least the contact distance is surely apart: no energy, no Hessian,
    // no closest points to find (half the measurements; a quarter of the basketweave table's CPU).
    static constexpr double kRounding = 1e-9;
    bool surelyApart(double bound, double D) const { return c.opt.skipPairsSurelyApart && bound >= D; }

    // Energy and its gradient with respect to the deformed vertices (gx); *dmin the smallest
    // distance of a listed pair.
    double energy(const Vec& v, std::vector<glm::dvec3>& gx, double& dmin) {
        ++evaluations;
        deform(v);
        gx.assign(c.n, glm::dvec3(0.0));
        double e = 0;
        const LatticeRelaxOptions& o = c.opt;
        for (size_t k = 0; k < c.n; ++k) {  // inextensibility
            const Seg& s = c.segs[k];
            const glm::dvec3 d = segEnd(s) - x[s.a];
            const double l = glm::length(d), strain = l / c.rest[k] - 1;
            e += o.stretch * c.rest[k] * strain * strain;
            const glm::dvec3 gd = (2 * o.stretch * strain / std::max(l, 1e-12)) * d;
            gx[s.b] += gd;
            gx[s.a] -= gd;
        }
        const double w = o.bend / (c.meanRest * c.meanRest * c.meanRest);
        for (size_t i = 0; i < c.n; ++i) {  // bending
            const Seg &in = c.before[i], &out = c.segs[i];
            const glm::dvec3 b = (x[in.a] - shift(in.dx, in.dy)) - 2.0 * x[i] + segEnd(out);
            e += w * glm::dot(b, b);
            const glm::dvec3 gb = 2 * w * b;
            gx[in.a] += gb;
            gx[out.b] += gb;
            gx[i] -= 2.0 * gb;
        }
        dmin = std::numeric_limits<double>::infinity();
        const double D = o.contactDistance, moved = slack() + kRounding;
        double skippedBound = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < pairs.size(); ++k) {  // contact
            const Pair& pr = pairs[k];
            const double bound = builtDistance[k] - moved;
            if (surelyApart(bound, D)) {
                skippedBound = std::min(skippedBound, bound);
                continue;
            }
            const Seg &s = c.segs[pr.s], &t = c.segs[pr.t];
            const auto [a, b, d, dist] = closest(pr);
            dmin = std::min(dmin, dist);
            if (dist >= D) continue;
            const ContactTerm ct = contactTerm(o, dist);
            e += ct.e;
            const glm::dvec3 gd = (ct.de / std::max(dist, 1e-12)) * d;
            gx[s.a] += (1 - a) * gd;
            gx[s.b] += a * gd;
            gx[t.a] -= (1 - b) * gd;
            gx[t.b] -= b * gd;
        }
        // dmin exactly as over every pair: the skipped ones that might be closer measured too.
        if (skippedBound < dmin)
            for (size_t k = 0; k < pairs.size(); ++k) {
                const double bound = builtDistance[k] - moved;
                if (surelyApart(bound, D) && bound < dmin) dmin = std::min(dmin, distance(pairs[k]));
            }
        return e;
    }

    // The energy's Hessian with respect to the reference-space unknowns at the last evaluation
    // (its x), each term's deformed-space block pulled back through M (M^T A M), handed to
    // add(i, j, coef, A) block by block (blocks (i, j) of blockPattern only). Projected to be
    // positive semi-definite per term: a compressed segment's and a contact's transverse
    // (negative) parts are left out, so that a Newton step is a descent direction.
    template <class Add>
    void hessian(const Add& add) const {
        const LatticeRelaxOptions& o = c.opt;
        const glm::dmat3 Mt = glm::transpose(M);
        const auto outer = [](const glm::dvec3& a) { return glm::outerProduct(a, a); };
        for (size_t k = 0; k < c.n; ++k) {  // inextensibility
            const Seg& sg = c.segs[k];
            const glm::dvec3 d = segEnd(sg) - x[sg.a];
            const double l = std::max(glm::length(d), 1e-12);
            const glm::dvec3 u = d / l;
            const double along = 2 * o.stretch / c.rest[k];
            const double across = along * std::max(0.0, (l - c.rest[k]) / l);
            const glm::dmat3 A = Mt * (along * outer(u) + across * (glm::dmat3(1.0) - outer(u))) * M;
            add(sg.a, sg.a, 1, A);
            add(sg.b, sg.b, 1, A);
            add(sg.a, sg.b, -1, A);
            add(sg.b, sg.a, -1, A);
        }
        const double w = o.bend / (c.meanRest * c.meanRest * c.meanRest);
        const glm::dmat3 B = Mt * glm::dmat3(2 * w) * M;
        for (size_t i = 0; i < c.n; ++i) {  // bending: b = x_in - 2 x_i + x_out
            const uint32_t idx[3] = {c.before[i].a, uint32_t(i), c.segs[i].b};
            const double coef[3] = {1, -2, 1};
            for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q) add(idx[r], idx[q], coef[r] * coef[q], B);
        }
        const double D = o.contactDistance, moved = slack() + kRounding;
        for (size_t k = 0; k < pairs.size(); ++k) {  // contact, with the closest points' parameters held fixed
            const Pair& pr = pairs[k];
            if (surelyApart(builtDistance[k] - moved, D)) continue;
            const Seg &sa = c.segs[pr.s], &tb = c.segs[pr.t];
            const auto [a, b, d, dist] = closest(pr);
            if (dist >= D || dist < 1e-12) continue;
            const glm::dmat3 A = Mt * (contactTerm(o, dist).d2e * outer(d / dist)) * M;
            const uint32_t idx[4] = {sa.a, sa.b, tb.a, tb.b};
            const double coef[4] = {1 - a, a, -(1 - b), -b};
            for (int r = 0; r < 4; ++r)
                for (int q = 0; q < 4; ++q) add(idx[r], idx[q], coef[r] * coef[q], A);
        }
    }

    // hessian() as triplets (the dense path's input), zero entries left out.
    void hessian(std::vector<Eigen::Triplet<double>>& h) const {
        h.clear();
        hessian([&](uint32_t i, uint32_t j, double coef, const glm::dmat3& A) {
            for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q) {
                    const double value = coef * A[q][r];  // glm is column-major: A[column][row]
                    if (value != 0)
                        h.emplace_back(Eigen::Index(3 * i + uint32_t(r)), Eigen::Index(3 * j + uint32_t(q)), value);
                }
        });
    }

    // The gradient with respect to the reference-space unknowns: M^T gx.
    void pullBack(const std::vector<glm::dvec3>& gx, Vec& g) const {
        g.resize(Eigen::Index(3 * c.n));
        const glm::dmat3 Mt = glm::transpose(M);
        for (size_t i = 0; i < c.n; ++i) {
            const glm::dvec3 r = Mt * gx[i];
            for (int k = 0; k < 3; ++k) g[Eigen::Index(3 * i + size_t(k))] = r[k];
        }
    }

    // The largest deformed move of a vertex for a reference-space step d.
    double largestMove(const Vec& d) const {
        double m = 0;
        for (size_t i = 0; i < c.n; ++i)
            m = std::max(m, glm::length(M * glm::dvec3(d[Eigen::Index(3 * i)], d[Eigen::Index(3 * i + 1)],
                                                       d[Eigen::Index(3 * i + 2)])));
        return m;
    }
};

double smallestSingularValue(const glm::dmat2& F) {
    const glm::dmat2 C = glm::transpose(F) * F;
    const double tr = C[0][0] + C[1][1], det = C[0][0] * C[1][1] - C[0][1] * C[1][0];
    const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    return std::sqrt(std::max(0.0, 0.5 * tr - disc));
}

}  // namespace

LatticeCell::LatticeCell(const Pattern& p, const LatticeRelaxOptions& options) : impl_(std::make_unique<Impl>()) {
    validatePattern(p, p.name);
    Impl& c = *impl_;
    c.opt = options;
    if (!(options.stretch > 0) || !(options.bend >= 0) || !(options.contact >= 0) || !(options.contactDistance > 0) ||
        options.maxIterations < 0 || !(options.maxStep > 0) || !(options.restLengthScale > 0))
        throw Error("lattice relaxation: the weights must be >= 0 (stretch > 0), the contact distance, the "
                    "largest step and the rest length scale positive and the iteration count >= 0");
    c.n = p.points.size();
    c.radius = p.radius;
    c.px = p.px / p.radius;
    c.py = p.py / p.radius;
    if (p.edges.size() != c.n) throw Error(p.name + ": relaxation needs closed yarns (every vertex starts one edge)");
    c.segs.resize(c.n);
    std::vector<int> seen(c.n, 0);
    for (const PeriodicEdge& e : p.edges) {
        if (seen[e.v0]++)
            throw Error(p.name + ": relaxation needs closed yarns with consistently oriented edges (vertex " +
                        std::to_string(e.v0) + ")");
        c.segs[e.v0] = {e.v0, e.v1, e.dx, e.dy};
    }
    c.yarns = relax::indexYarns(p, c.segs);
    for (int32_t len : c.yarns.length)
        if (len < 4) throw Error(p.name + ": relaxation needs yarns of at least 4 vertices");
    c.before.resize(c.n);
    for (const Seg& s : c.segs) c.before[s.b] = s;
    c.start.resize(c.n);
    for (size_t i = 0; i < c.n; ++i) c.start[i] = p.points[i] / p.radius;
    double total = 0;
    for (const Seg& s : c.segs) {
        const glm::dvec3 end = c.start[s.b] + glm::dvec3(s.dx * c.px, s.dy * c.py, 0);
        c.rest.push_back(options.restLengthScale * glm::length(end - c.start[s.a]));
        total += c.rest.back();
    }
    c.meanRest = total / double(c.n);
}

LatticeCell::~LatticeCell() = default;

size_t LatticeCell::vertexCount() const { return impl_->n; }

namespace {

// Sets the lattice map of a relaxation.
void setLattice(State& st, const glm::dmat2& F) {
    st.M = glm::dmat3(glm::dvec3(F[0], 0.0), glm::dvec3(F[1], 0.0), glm::dvec3(0, 0, 1));
    st.a1 = st.M * glm::dvec3(st.c.px, 0, 0);
    st.a2 = st.M * glm::dvec3(0, st.c.py, 0);
    st.sigmaMin = smallestSingularValue(F);
}

struct Stage {
    int iterations = 0;
    bool converged = false;
    double energy = 0;
};

// The sparse path's Newton steps: conjugate gradients on a kept factor. Cells of over 200
// vertices solve to a tenth of the gradient's norm (1e-2 took 31 % more CPU for the same
// iterations and minima, docs/deformation.md "Levers"); smaller ones to 1e-4 with 20 iterations
// before a new factor, so that they settle where the dense Cholesky step did (seed, rib2x2:
// per-sample medians 1e-6 r from it; the looser solve moved seed's compressed samples to other
// branches, up to 6 r; "Cells of 100-200 vertices").
BlockSolveOptions newtonSolve(size_t n) { return n > 200 ? BlockSolveOptions{0.1, 8} : BlockSolveOptions{1e-4, 20}; }

// The Newton system H d = -g of one lattice stage: small cells a dense Cholesky factorisation of
// the Hessian plus mu I (cheaper than any sparse analysis), larger ones a step by conjugate
// gradients on an earlier iteration's sparse factor (block_hessian.hpp, newtonSolve).
struct NewtonSystem {
    bool dense;
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::MatrixXd Hd;
    Eigen::LLT<Eigen::MatrixXd> denseSolver;
    BlockHessian sparse;

    NewtonSystem(size_t n, LatticeRelaxOptions::Newton path)
        : dense(path == LatticeRelaxOptions::Newton::BySize ? denseNewton(n)
                                                            : path == LatticeRelaxOptions::Newton::Dense) {
        if (dense) Hd.resize(Eigen::Index(3 * n), Eigen::Index(3 * n));
    }
    // The Newton step at the state's last evaluation; empty where the factorisation fails.
    Vec step(const State& st, double mu, const Vec& g) {
        if (!dense) {
            sparse.clear(st.c.n);
            st.hessian([&](uint32_t i, uint32_t j, double coef, const glm::dmat3& A) { sparse.add(i, j, coef, A); });
            const Vec d = sparse.solve(g, mu, newtonSolve(st.c.n));
            return d.size() == 0 ? d : Vec(-d);
        }
        st.hessian(triplets);
        for (Eigen::Index i = 0; i < Hd.rows(); ++i) triplets.emplace_back(i, i, mu);
        Hd.setZero();
        for (const Eigen::Triplet<double>& t : triplets) Hd(t.row(), t.col()) += t.value();
        denseSolver.compute(Hd);
        return denseSolver.info() == Eigen::Success ? Vec(-denseSolver.solve(g)) : Vec();
    }
};

// Damped Newton on one lattice from v: the projected Hessian (State::hessian) plus mu I (mu raised
// while the step fails, lowered while it succeeds), a backtracking line search, and every step
// capped so that no two segments move by more than 0.9 of their distance (the lattice is fixed
// here, so two points of two segments come closer by at most twice the largest vertex move).
Stage newton(State& st, Vec& v, int maxIterations, double tolerance) {
    const Impl& c = st.c;
    const LatticeRelaxOptions& o = c.opt;
    const double skin = 1.0, cutoff = o.contactDistance + skin;
    st.deform(v);
    st.findPairs(v, cutoff);
    std::vector<glm::dvec3> gx;
    double dmin = 0, dminNew = 0;
    Vec g, gNew, vNew;
    double e = st.energy(v, gx, dmin);
    st.pullBack(gx, g);
    NewtonSystem system(c.n, o.newton);
    Stage stage;
    double mu = 1e-6;
    double drift = 0;
    int it = 0;
    for (; it < maxIterations; ++it) {
        if (g.lpNorm<Eigen::Infinity>() < tolerance) {
            stage.converged = true;
            break;
        }
        Vec d = system.step(st, mu, g);
        if (d.size() != 0) {  // a translation of the whole cell changes nothing: not part of the step
            const Eigen::Vector3d mean = d.reshaped(3, Eigen::Index(c.n)).rowwise().mean();
            d.reshaped(3, Eigen::Index(c.n)).colwise() -= mean;
        }
        if (d.size() == 0 || !d.allFinite() || d.dot(g) >= 0) {
            mu = std::max(mu * 10, 1e-3);
            if (mu > 1e12) break;
            continue;
        }
        const double move = std::max(st.largestMove(d), 1e-300);
        double step = std::min({1.0, o.maxStep / move, 0.45 * std::min(dmin, cutoff - drift) / move});
        double eNew = e;
        bool accepted = false;
        for (int k = 0; k < 30 && !accepted; ++k) {
            if (k > 0) step *= 0.5;
            vNew = v + step * d;
            eNew = st.energy(vNew, gx, dminNew);
            accepted = eNew <= e + 1e-4 * step * d.dot(g);
        }
        if (!accepted) {
            st.energy(v, gx, dmin);  // restore the state of v
            mu = std::max(mu * 10, 1e-3);
            if (mu > 1e12) {
                stage.converged = true;  // no descent even along a gradient step: a minimum to round-off
                break;
            }
            continue;
        }
        mu = std::max(mu * 0.3, 1e-6);
        st.pullBack(gx, gNew);
        v.swap(vNew);
        g.swap(gNew);
        e = eNew;
        dmin = dminNew;
        // Pairs outside the list were `cutoff` apart when it was built and came closer by at most
        // twice the largest move since; rebuilt when that reaches half the skin.
        drift = st.slack();
        if (drift > 0.5 * skin) {
            st.findPairs(v, cutoff);
            drift = 0;
            e = st.energy(v, gx, dmin);
            st.pullBack(gx, g);
        }
    }
    stage.iterations = it;
    stage.energy = e;
    return stage;
}

}  // namespace

LatticeRelaxResult LatticeCell::relax(const glm::dmat2& F, const std::vector<glm::dvec3>& startPoints,
                                      const glm::dmat2& startLattice) const {
    const Impl& c = *impl_;
    if (!startPoints.empty() && startPoints.size() != c.n)
        throw Error("lattice relaxation: " + std::to_string(startPoints.size()) + " start points for " +
                    std::to_string(c.n) + " vertices");
    if (!(std::abs(glm::determinant(F)) > 1e-9) || !(std::abs(glm::determinant(startLattice)) > 1e-9))
        throw Error("lattice relaxation: the lattice map is singular");
    State st(c);
    Vec v(Eigen::Index(3 * c.n));
    for (size_t i = 0; i < c.n; ++i) {
        const glm::dvec3 p = startPoints.empty() ? c.start[i] : startPoints[i] / c.radius;
        for (int k = 0; k < 3; ++k) v[Eigen::Index(3 * i + size_t(k))] = p[k];
    }
    // The lattice moves from the start's to F in stages, each relaxed (the crossings are kept
    // while the lattice moves, not only within a relaxation).
    const glm::dmat2 change = F - startLattice;
    const int stages = latticeStages(F, startLattice);
    LatticeRelaxResult result;
    result.stages = stages;
    Stage stage;
    for (int k = 1; k <= stages; ++k) {
        setLattice(st, startLattice + (double(k) / double(stages)) * change);
        // The stages on the way only need to follow the lattice: a looser tolerance.
        const bool last = k == stages;
        stage = newton(st, v, last ? c.opt.maxIterations : c.opt.maxIterations / 4 + 1,
                       last ? c.opt.gradientTolerance : 10 * c.opt.gradientTolerance);
        result.iterations += stage.iterations;
    }
    result.converged = stage.converged;
    result.energy = stage.energy;
    result.pairsMeasured = st.measured;
    st.deform(v);
    st.findPairs(v, 6.0);
    double closest = std::numeric_limits<double>::infinity();
    for (const Pair& pr : st.pairs) closest = std::min(closest, st.distance(pr));
    result.minDistance = closest;
    result.points.resize(c.n);
    for (size_t i = 0; i < c.n; ++i)
        result.points[i] =
            glm::dvec3(v[Eigen::Index(3 * i)], v[Eigen::Index(3 * i + 1)], v[Eigen::Index(3 * i + 2)]) * c.radius;
    return result;
}

int latticeStages(const glm::dmat2& F, const glm::dmat2& start) {
    const glm::dmat2 change = F - start;
    const double size = std::sqrt(glm::dot(change[0], change[0]) + glm::dot(change[1], change[1]));
    const double sigma = std::min({smallestSingularValue(F), smallestSingularValue(start), 1.0});
    return std::max(1, int(std::ceil(size / (0.1 * sigma))));
}

std::vector<glm::dvec3> restCell(const Pattern& pattern, const LatticeRelaxOptions& options) {
    LatticeRelaxOptions o = options;
    o.maxIterations = 8 * options.maxIterations;
    // Far below the samples' tolerance: the rest shape is a minimum to round-off, the same (to
    // far below a micrometre) whichever compiler made it.
    o.gradientTolerance = 1e-3 * options.gradientTolerance;
    return LatticeCell(pattern, o).relax(glm::dmat2(1.0), {}).points;
}

double cellYarnLength(const Pattern& pattern, const std::vector<glm::dvec3>& points, const glm::dmat2& F) {
    double total = 0;
    for (const PeriodicEdge& e : pattern.edges) {
        const glm::dvec3 d = points[e.v1] + glm::dvec3(e.dx * pattern.px, e.dy * pattern.py, 0) - points[e.v0];
        total += glm::length(glm::dvec3(F * glm::dvec2(d.x, d.y), d.z));
    }
    return total;
}

}  // namespace knit::impl
