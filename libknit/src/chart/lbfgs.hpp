// lbfgs.hpp — the limited-memory BFGS pieces both cell relaxations use (relax.cpp on the free
// period, relax_lattice.cpp on a prescribed deformed lattice): the search direction from the
// remembered steps, and the memory update.
#pragma once
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace knit::relax {

// The two-loop recursion (Nocedal & Wright, algorithm 7.4): -H g from the steps S and the
// gradient changes Y, oldest first, with H0 q = initial(q) as the initial inverse Hessian (a
// preconditioner).
template <class Initial>
Eigen::VectorXd lbfgsDirection(const Eigen::VectorXd& g, const std::vector<Eigen::VectorXd>& S,
                               const std::vector<Eigen::VectorXd>& Y, const Initial& initial) {
    Eigen::VectorXd q = g;
    std::vector<double> alpha(S.size());
    for (size_t i = S.size(); i-- > 0;) {
        alpha[i] = S[i].dot(q) / Y[i].dot(S[i]);
        q -= alpha[i] * Y[i];
    }
    q = initial(q);
    for (size_t i = 0; i < S.size(); ++i) q += (alpha[i] - Y[i].dot(q) / Y[i].dot(S[i])) * S[i];
    return -q;
}

// The same with the usual scaled identity, H0 = (s.y / y.y) I from the last pair.
inline Eigen::VectorXd lbfgsDirection(const Eigen::VectorXd& g, const std::vector<Eigen::VectorXd>& S,
                                      const std::vector<Eigen::VectorXd>& Y) {
    const double scale = S.empty() ? 1.0 : S.back().dot(Y.back()) / Y.back().dot(Y.back());
    return lbfgsDirection(g, S, Y, [scale](const Eigen::VectorXd& q) -> Eigen::VectorXd { return scale * q; });
}

// Remembers the step s and gradient change y unless their curvature is not positive (the
// update would not be positive definite); keeps the last `memory` pairs.
inline void lbfgsRemember(std::vector<Eigen::VectorXd>& S, std::vector<Eigen::VectorXd>& Y, Eigen::VectorXd s,
                          Eigen::VectorXd y, size_t memory = 8) {
    if (y.dot(s) <= 1e-300) return;
    S.push_back(std::move(s));
    Y.push_back(std::move(y));
    if (S.size() > memory) {
        S.erase(S.begin());
        Y.erase(Y.begin());
    }
}

}  // namespace knit::relax
