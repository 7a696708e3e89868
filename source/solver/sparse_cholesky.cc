#include <ritr/common/thread_pools.h>
#include <ritr/solver/sparse_cholesky.h>

#include <algorithm>
#include <stdexcept>

namespace ritr
{
  SparseCholesky::SparseCholesky()
  {
    llt_.setMode(Eigen::CholmodAuto);
    llt_.cholmod().supernodal_switch = 100;  // flops per factor entry (header)
    // LL' in both kinds: a matrix that is not positive definite fails, and gets shifted, in
    // both (simplicial LDL' would accept an indefinite one).
    llt_.cholmod().final_asis = 0;
    llt_.cholmod().final_ll   = 1;
  }

  bool SparseCholesky::same_pattern(const Eigen::SparseMatrix<double> &m) const
  {
    return analysed_ && static_cast<std::size_t>(m.outerSize() + 1) == outer_.size() &&
           static_cast<std::size_t>(m.nonZeros()) == inner_.size() &&
           std::equal(outer_.begin(), outer_.end(), m.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), m.innerIndexPtr());
  }

  double SparseCholesky::factorize(const Eigen::SparseMatrix<double> &matrix)
  {
    if (!matrix.isCompressed())
      throw std::logic_error("SparseCholesky needs a compressed matrix");
    if (matrix.rows() == 0)
      return 0.0;  // every entry prescribed: nothing to factorize (CHOLMOD fails on it)
    if (!same_pattern(matrix))
      {
        llt_.analyzePattern(matrix);
        analysed_flops_ = llt_.cholmod().fl;
        outer_.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + matrix.outerSize() + 1);
        inner_.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
        analysed_ = true;
        ++n_analyses_;
      }
    const LargeFactorizationThreads blas_threads(analysed_flops_);
    // A failed attempt is expected here (print 0: no warning on stderr).
    const auto factorize_shifted = [&](const double shift) {
      llt_.cholmod().print = 0;
      llt_.setShift(shift);
      llt_.factorize(matrix);
      ++n_factorizations_;
      return llt_.info() == Eigen::Success;
    };
    if (factorize_shifted(0.0))
      return 0.0;
    // Projected Hessians are only semi-definite (e.g. statics with a free rigid mode):
    // regularise relative to the diagonal's scale.
    const double scale = std::max(matrix.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    for (double shift = 1e-12 * scale; shift < 1e6 * scale; shift *= 100)
      if (factorize_shifted(shift))
        return shift;
    throw std::runtime_error("the Newton system could not be factorized");
  }

  Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd &rhs) const
  {
    return rhs.size() == 0 ? rhs : Eigen::VectorXd(llt_.solve(rhs));
  }

  Eigen::MatrixXd SparseCholesky::solve_columns(const Eigen::MatrixXd &rhs) const
  {
    return rhs.size() == 0 ? rhs : Eigen::MatrixXd(llt_.solve(rhs));
  }
} // namespace ritr
