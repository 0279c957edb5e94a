// A periodic cell relaxed on a prescribed, deformed lattice (see relax_lattice.hpp): the energy of
// chart relaxation on the yarn M Y, minimised over the reference-space vertices Y.
#include "relax_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "knit/error.hpp"
#include "lbfgs.hpp"
#include "relax_contact.hpp"

namespace knit::impl {

using relax::lbfgsDirection;
using relax::lbfgsRemember;
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

// One relaxation: the map, the lattice and the contact pairs.
struct State {
    const Impl& c;
    glm::dmat3 M{1.0};
    glm::dvec3 a1{0.0}, a2{0.0};  // deformed lattice vectors (radii)
    double sigmaMin = 1;          // smallest singular value of F
    std::vector<Pair> pairs;
    std::vector<glm::dvec3> x;  // deformed vertices (radii), of the last evaluation
    int evaluations = 0;

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
        for (uint32_t s = 0; s < c.n; ++s)
            for (uint32_t t = s; t < c.n; ++t)
                for (int iy = -ky; iy <= ky; ++iy)
                    for (int ix = -kx; ix <= kx; ++ix) {
                        if (t == s && (iy < 0 || (iy == 0 && ix <= 0))) continue;
                        const double reachPair = cutoff + half[s] + half[t];
                        const glm::dvec3 apart = mid[t] + shift(ix, iy) - mid[s];
                        if (glm::dot(apart, apart) >= reachPair * reachPair) continue;
                        const Pair pr{s, t, ix, iy};
                        if (relax::nearAlongYarn(c.yarns, c.segs, pr, 3)) continue;
                        if (distance(pr) < cutoff) pairs.push_back(pr);
                    }
    }

    double distance(const Pair& pr) const {
        const Seg &s = c.segs[pr.s], &t = c.segs[pr.t];
        const glm::dvec3 p0 = x[s.a], p1 = segEnd(s), q0 = x[t.a] + shift(pr.ix, pr.iy),
                         q1 = segEnd(t) + shift(pr.ix, pr.iy);
        double a = 0, b = 0;
        relax::closestParameters(p0, p1, q0, q1, a, b);
        return glm::length((p0 + a * (p1 - p0)) - (q0 + b * (q1 - q0)));
    }

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
        const double D = o.contactDistance;
        for (const Pair& pr : pairs) {  // contact
            const Seg &s = c.segs[pr.s], &t = c.segs[pr.t];
            const glm::dvec3 p0 = x[s.a], p1 = segEnd(s), q0 = x[t.a] + shift(pr.ix, pr.iy),
                             q1 = segEnd(t) + shift(pr.ix, pr.iy);
            double a = 0, b = 0;
            relax::closestParameters(p0, p1, q0, q1, a, b);
            const glm::dvec3 d = (p0 + a * (p1 - p0)) - (q0 + b * (q1 - q0));
            const double dist = glm::length(d);
            dmin = std::min(dmin, dist);
            if (dist >= D) continue;
            e += o.contact * (D - dist) * (D - dist);
            const glm::dvec3 gd = (-2 * o.contact * (D - dist) / std::max(dist, 1e-12)) * d;
            gx[s.a] += (1 - a) * gd;
            gx[s.b] += a * gd;
            gx[t.a] -= (1 - b) * gd;
            gx[t.b] -= b * gd;
        }
        return e;
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
        options.maxIterations < 0 || !(options.maxStep > 0))
        throw Error("lattice relaxation: the weights must be >= 0 (stretch > 0), the contact distance and the "
                    "largest step positive and the iteration count >= 0");
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
        c.rest.push_back(glm::length(end - c.start[s.a]));
        total += c.rest.back();
    }
    c.meanRest = total / double(c.n);
}

LatticeCell::~LatticeCell() = default;

size_t LatticeCell::vertexCount() const { return impl_->n; }

LatticeRelaxResult LatticeCell::relax(const glm::dmat2& F, const std::vector<glm::dvec3>& startPoints) const {
    const Impl& c = *impl_;
    if (!startPoints.empty() && startPoints.size() != c.n)
        throw Error("lattice relaxation: " + std::to_string(startPoints.size()) + " start points for " +
                    std::to_string(c.n) + " vertices");
    if (!(std::abs(glm::determinant(F)) > 1e-9)) throw Error("lattice relaxation: the lattice map is singular");
    State st(c);
    st.M = glm::dmat3(glm::dvec3(F[0], 0.0), glm::dvec3(F[1], 0.0), glm::dvec3(0, 0, 1));
    st.a1 = st.M * glm::dvec3(c.px, 0, 0);
    st.a2 = st.M * glm::dvec3(0, c.py, 0);
    st.sigmaMin = smallestSingularValue(F);
    Vec v(Eigen::Index(3 * c.n));
    for (size_t i = 0; i < c.n; ++i) {
        const glm::dvec3 p = startPoints.empty() ? c.start[i] : startPoints[i] / c.radius;
        for (int k = 0; k < 3; ++k) v[Eigen::Index(3 * i + size_t(k))] = p[k];
    }
    const LatticeRelaxOptions& o = c.opt;
    const double skin = 1.0, cutoff = o.contactDistance + skin;
    st.deform(v);
    st.findPairs(v, cutoff);
    std::vector<glm::dvec3> built = st.x, gx;
    double dmin = 0, dminNew = 0;
    Vec g, gNew, vNew;
    double e = st.energy(v, gx, dmin);
    st.pullBack(gx, g);
    std::vector<Vec> S, Y;
    LatticeRelaxResult result;
    int it = 0;
    double drift = 0;
    for (; it < o.maxIterations; ++it) {
        if (g.lpNorm<Eigen::Infinity>() < o.gradientTolerance) {
            result.converged = true;
            break;
        }
        Vec d = lbfgsDirection(g, S, Y);
        if (d.dot(g) >= 0) {
            S.clear();
            Y.clear();
            d = -g;
        }
        // Capped by the largest move and by the collision bound: two points of two segments come
        // closer by at most 2 x the largest vertex move (the lattice is fixed).
        const double move = std::max(st.largestMove(d), 1e-300);
        double step = std::min({1.0, o.maxStep / move, 0.45 * std::min(dmin, cutoff - drift) / move});
        double eNew = e;
        bool accepted = false;
        for (int k = 0; k < 40 && !accepted; ++k) {
            if (k > 0) step *= 0.5;
            vNew = v + step * d;
            eNew = st.energy(vNew, gx, dminNew);
            accepted = eNew <= e + 1e-4 * step * d.dot(g);
        }
        if (!accepted) {
            if (S.empty()) {
                result.converged = true;  // no descent even along -g: a minimum to round-off
                break;
            }
            S.clear();
            Y.clear();
            st.energy(v, gx, dmin);  // restore the state of v
            continue;
        }
        st.pullBack(gx, gNew);
        lbfgsRemember(S, Y, vNew - v, gNew - g);
        v.swap(vNew);
        g.swap(gNew);
        e = eNew;
        dmin = dminNew;
        // Pairs outside the list were `cutoff` apart when it was built and came closer by at most
        // twice the largest move since; rebuilt when that reaches half the skin.
        double m = 0;
        for (size_t i = 0; i < c.n; ++i) m = std::max(m, glm::length(st.x[i] - built[i]));
        drift = 2 * m;
        if (drift > 0.5 * skin) {
            st.findPairs(v, cutoff);
            built = st.x;
            drift = 0;
            e = st.energy(v, gx, dmin);
            st.pullBack(gx, g);
        }
    }
    result.iterations = it;
    result.energy = e;
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

}  // namespace knit::impl
