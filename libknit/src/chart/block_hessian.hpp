// block_hessian.hpp (internal) — the large cells' Newton systems (relax_lattice.cpp): a symmetric
// positive semi-definite matrix given as a list of 3 x 3 blocks, plus mu I, solved by conjugate
// gradients preconditioned with the sparse LDLᵀ factor of an earlier iteration's matrix (an
// inexact Newton step), the factor renewed only when that does not reach the tolerance in a few
// iterations. A factorisation of the 1152 x 1152 Hessian of a 384-vertex cell costs about as much
// as fifty of those iterations; nearby Newton iterations have nearly the same Hessian.
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <glm/mat3x3.hpp>

namespace knit::impl {

struct BlockSolveOptions {
    double tolerance = 1e-2;  // residual over the right-hand side's norm, for a preconditioned solve
    int maxIterations = 8;    // conjugate-gradient iterations before the factor is renewed
};

class BlockHessian {
public:
    // Empties the block list for a matrix of n block rows and columns.
    void clear(size_t n);
    // Adds coef A to block (i, j) (A is glm's column-major matrix).
    void add(uint32_t i, uint32_t j, double coef, const glm::dmat3& A) { blocks_.push_back({i, j, coef * A}); }

    // x solving (blocks + mu I) x = b: by conjugate gradients preconditioned with the kept factor,
    // else (or without one) a new factor of this matrix. Empty where the factorisation fails.
    Eigen::VectorXd solve(const Eigen::VectorXd& b, double mu, const BlockSolveOptions& options = {});

    int factorizations() const { return factorizations_; }

private:
    struct Block {
        uint32_t i, j;
        glm::dmat3 A;
    };
    void multiply(const Eigen::VectorXd& v, double mu, Eigen::VectorXd& out) const;
    bool preconditioned(const Eigen::VectorXd& b, double mu, const BlockSolveOptions& o, Eigen::VectorXd& x) const;
    bool factorize(double mu);

    size_t n_ = 0;
    std::vector<Block> blocks_;
    bool haveFactor_ = false;
    int factorizations_ = 0;
    std::vector<Eigen::Triplet<double>> triplets_;
    Eigen::SparseMatrix<double> h_;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace knit::impl
