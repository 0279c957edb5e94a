// BlockHessian (chart/block_hessian.hpp): the large lattice cells' Newton systems, solved by
// conjugate gradients on an earlier matrix's factor or by a new factor.
#include <gtest/gtest.h>

#include <cstdint>

#include <Eigen/Core>
#include <glm/mat3x3.hpp>

#include "chart/block_hessian.hpp"

namespace {

// A chain of n blocks coupled to their neighbours (a closed yarn's stretch terms, stiffness k),
// plus a softer coupling of every block to the one n/2 away (contacts).
void fill(knit::impl::BlockHessian& h, uint32_t n, double k) {
    h.clear(n);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = (i + 1) % n, far = (i + n / 2) % n;
        const glm::dmat3 A(glm::dvec3(k, 0.1 * k, 0), glm::dvec3(0.1 * k, k, 0), glm::dvec3(0, 0, 0.5 * k));
        h.add(i, i, 1, A);
        h.add(j, j, 1, A);
        h.add(i, j, -1, A);
        h.add(j, i, -1, A);
        const glm::dmat3 B(0.3 + 0.01 * i);
        h.add(i, i, 1, B);
        h.add(far, far, 1, B);
        h.add(i, far, -1, B);
        h.add(far, i, -1, B);
    }
}

// ||(H + mu I) x - b|| / ||b|| for the matrix fill(n, k) builds, its product formed here by hand.
double residual(uint32_t n, double k, double mu, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
    Eigen::VectorXd y = mu * x;
    const auto apply = [&](uint32_t i, uint32_t j, const glm::dmat3& A) {
        const glm::dvec3 v = A * glm::dvec3(x[3 * j], x[3 * j + 1], x[3 * j + 2]);
        for (int r = 0; r < 3; ++r) y[3 * i + r] += v[r];
    };
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = (i + 1) % n, far = (i + n / 2) % n;
        const glm::dmat3 A(glm::dvec3(k, 0.1 * k, 0), glm::dvec3(0.1 * k, k, 0), glm::dvec3(0, 0, 0.5 * k));
        apply(i, i, A), apply(j, j, A), apply(i, j, -A), apply(j, i, -A);
        const glm::dmat3 B(0.3 + 0.01 * i);
        apply(i, i, B), apply(far, far, B), apply(i, far, -B), apply(far, i, -B);
    }
    return (y - b).norm() / b.norm();
}

TEST(BlockHessian, solvesByANewFactorThenByConjugateGradientsOnIt) {
    const uint32_t n = 60;
    const double mu = 1e-3;
    knit::impl::BlockHessian h;
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * n, -1.0, 2.0);
    fill(h, n, 100);
    const Eigen::VectorXd x0 = h.solve(b, mu);
    ASSERT_EQ(x0.size(), b.size());
    EXPECT_EQ(h.factorizations(), 1);
    EXPECT_LT(residual(n, 100, mu, x0, b), 1e-9);  // a direct solve
    // A slightly different matrix: the kept factor preconditions, no new factorisation, the
    // residual within the tolerance.
    fill(h, n, 101);
    const Eigen::VectorXd x1 = h.solve(b, 2 * mu);
    EXPECT_EQ(h.factorizations(), 1);
    const double r1 = residual(n, 101, 2 * mu, x1, b);
    EXPECT_LT(r1, 1e-2);
    EXPECT_GT(r1, 1e-12);  // inexact: conjugate gradients stopped at the tolerance, not a new factor
    // A very different matrix: eight iterations do not reach the tolerance, so a new factor.
    fill(h, n, 1e5);
    const Eigen::VectorXd x2 = h.solve(b, mu);
    EXPECT_EQ(h.factorizations(), 2);
    EXPECT_LT(residual(n, 1e5, mu, x2, b), 1e-6);  // a direct solve (condition number about 1e8)
}

}  // namespace
