#pragma once
// Sparse Cholesky factorization with CHOLMOD, reusing the symbolic analysis for as long as the
// matrix keeps the same sparsity pattern (contact pairs change it). Supernodal. (Nearly
// diagonal matrices solved many times, where a solve's call overhead costs more than its
// arithmetic, have their own inverse: shifted_sparse_inverse.h.)
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
    double factorize(const Eigen::SparseMatrix<double> &matrix);
    Eigen::VectorXd solve(const Eigen::VectorXd &rhs) const;
    // Many right-hand sides in one call: CHOLMOD's blocked solve, far cheaper than a loop.
    Eigen::MatrixXd solve_columns(const Eigen::MatrixXd &rhs) const;

    unsigned int n_symbolic_analyses() const { return n_analyses_; }
    unsigned int n_factorizations() const { return n_factorizations_; }

  private:
    bool same_pattern(const Eigen::SparseMatrix<double> &matrix) const;

    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
    std::vector<int> outer_, inner_;
    bool             analysed_         = false;
    unsigned int     n_analyses_       = 0;
    unsigned int     n_factorizations_ = 0;
  };
} // namespace ritr
