#pragma once
// Sparse Cholesky factorization with CHOLMOD, reusing the symbolic analysis for as long as the
// matrix keeps the same sparsity pattern (contact pairs change it). CHOLMOD chooses between its
// simplicial and supernodal factorizations by the flops per factor entry, switching to
// supernodal at 100 (its default is 40): below that the supernodal one's calls cost more than
// they save. Measured per factorization: a 2D ball of 209 vertices 0.11 against 0.65 ms
// (ratio 25), of 801 vertices 0.9 against 1.9 ms (44), of 3,137 vertices 11 against 12 ms (93);
// above, a 3D wedge of 943 vertices 17 against 6.7 ms (182) and a 2D ball of 12,417 vertices
// 92 against 52 ms (186). (Nearly diagonal matrices solved many times, where a solve's call
// overhead costs more than its arithmetic, have their own inverse: shifted_sparse_inverse.h.)
// The fill-reducing ordering is CHOLMOD's default: AMD, and METIS as well when AMD's factor is
// large, the better of the two taken. In 3D that is METIS: on the 6,161-vertex drop-through
// (18,483 unknowns) AMD alone gives 1.22x the factor's entries and 1.6x its flops, and its first
// 25 steps' linear solves take 1.34x as long; METIS or NESDIS alone is within 4 % of the default.
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  class SparseCholesky
  {
  public:
    // Factorizes `matrix` (symmetric, lower triangle used). A matrix that is not positive
    // definite is regularised by adding a growing multiple of the identity; returns the
    // shift that was needed (0 for a positive definite matrix).
    SparseCholesky();
    double factorize(const Eigen::SparseMatrix<double> &matrix);
    Eigen::VectorXd solve(const Eigen::VectorXd &rhs) const;
    // Many right-hand sides in one call: CHOLMOD's blocked solve, far cheaper than a loop.
    Eigen::MatrixXd solve_columns(const Eigen::MatrixXd &rhs) const;

    unsigned int n_symbolic_analyses() const { return n_analyses_; }
    // The flops of a numeric factorization, by the last symbolic analysis.
    double factorization_flops() const { return analysed_flops_; }
    unsigned int n_factorizations() const { return n_factorizations_; }

  private:
    bool same_pattern(const Eigen::SparseMatrix<double> &matrix) const;

    Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
    std::vector<int> outer_, inner_;
    bool             analysed_         = false;
    double           analysed_flops_   = 0;  // of a factorization, by the symbolic analysis
    unsigned int     n_analyses_       = 0;
    unsigned int     n_factorizations_ = 0;
  };
} // namespace ritr
