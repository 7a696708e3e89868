#pragma once
// The inverse of M = sigma I + B, with sigma > 0 and B symmetric positive semi-definite and
// sparse, where B touches few unknowns: the outer trust region's CG preconditioner (B the
// measure barrier's Hessian on the cells near it, plus its secants). M is the identity times
// sigma on the unknowns B does not touch, so M^-1 v is v / sigma there and one small sparse
// Cholesky solve on the rest. A sparse factorization of all of M cost ~5 us per CG iteration,
// in call overhead; this costs a division per unknown and the touched unknowns' sweep.
#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  class ShiftedSparseInverse
  {
  public:
    // B's lower triangle is read.
    void factorize(double sigma, const Eigen::SparseMatrix<double> &B);
    Eigen::VectorXd solve(const Eigen::VectorXd &v) const;
    // The unknowns B touches.
    const std::vector<int> &touched() const { return touched_; }

  private:
    double                                                          sigma_ = 1;
    std::vector<int>                                                touched_;
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> block_;  // of sigma I + B on them
  };
} // namespace ritr
