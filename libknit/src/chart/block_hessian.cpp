// The large cells' Newton systems: block list, preconditioned conjugate gradients on a kept LDLᵀ
// factor (see block_hessian.hpp).
#include "block_hessian.hpp"

namespace knit::impl {

using Vec = Eigen::VectorXd;

void BlockHessian::clear(size_t n) {
    if (n != n_) haveFactor_ = false;
    n_ = n;
    blocks_.clear();
}

void BlockHessian::multiply(const Vec& v, double mu, Vec& out) const {
    out = mu * v;
    for (const Block& b : blocks_) {
        const glm::dvec3 x(v[Eigen::Index(3 * b.j)], v[Eigen::Index(3 * b.j + 1)], v[Eigen::Index(3 * b.j + 2)]);
        const glm::dvec3 y = b.A * x;
        for (int r = 0; r < 3; ++r) out[Eigen::Index(3 * b.i) + r] += y[r];
    }
}

// Conjugate gradients from x = 0, preconditioned with the kept factor; true when the residual
// reached the tolerance.
bool BlockHessian::preconditioned(const Vec& b, double mu, const BlockSolveOptions& o, Vec& x) const {
    const double target = o.tolerance * b.norm();
    x.setZero(b.size());
    Vec r = b, z = ldlt_.solve(r), p = z, q;
    double rz = r.dot(z);
    for (int k = 0; k < o.maxIterations; ++k) {
        multiply(p, mu, q);
        const double pq = p.dot(q);
        if (!(pq > 0) || !(rz > 0)) return false;  // not positive definite along p: renew the factor
        const double alpha = rz / pq;
        x += alpha * p;
        r -= alpha * q;
        if (r.norm() <= target) return x.allFinite();
        z = ldlt_.solve(r);
        const double rzNew = r.dot(z);
        p = z + (rzNew / rz) * p;
        rz = rzNew;
    }
    return false;
}

bool BlockHessian::factorize(double mu) {
    triplets_.clear();
    for (const Block& b : blocks_)
        for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) {
                const double value = b.A[q][r];  // glm is column-major: A[column][row]
                if (value != 0) triplets_.emplace_back(Eigen::Index(3 * b.i) + r, Eigen::Index(3 * b.j) + q, value);
            }
    for (Eigen::Index i = 0; i < Eigen::Index(3 * n_); ++i) triplets_.emplace_back(i, i, mu);
    h_.resize(Eigen::Index(3 * n_), Eigen::Index(3 * n_));
    h_.setFromTriplets(triplets_.begin(), triplets_.end());
    ldlt_.compute(h_);
    ++factorizations_;
    haveFactor_ = ldlt_.info() == Eigen::Success;
    return haveFactor_;
}

Vec BlockHessian::solve(const Vec& b, double mu, const BlockSolveOptions& options) {
    Vec x;
    if (haveFactor_ && preconditioned(b, mu, options, x)) return x;
    if (!factorize(mu)) return Vec();
    x = ldlt_.solve(b);
    return x;
}

}  // namespace knit::impl
