#include <ritr/solver/shifted_sparse_inverse.h>

#include <algorithm>
#include <stdexcept>

namespace ritr
{
  void ShiftedSparseInverse::factorize(const double sigma, const Eigen::SparseMatrix<double> &B)
  {
    if (!(sigma > 0))
      throw std::logic_error("ShiftedSparseInverse needs a positive shift");
    sigma_ = sigma;
    // One pass over B's lower triangle collects its entries and the unknowns they touch.
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<int>                    local(B.rows(), -1);
    touched_.clear();
    for (Eigen::Index c = 0; c < B.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(B, c); it; ++it)
        if (it.row() >= it.col() && it.value() != 0)
          {
            entries.emplace_back(it.row(), it.col(), it.value());
            for (const Eigen::Index i : {it.row(), it.col()})
              if (local[i] < 0)
                {
                  local[i] = 0;
                  touched_.push_back(int(i));
                }
          }
    if (touched_.empty())
      return;
    std::sort(touched_.begin(), touched_.end());
    for (std::size_t a = 0; a < touched_.size(); ++a)
      local[touched_[a]] = int(a);
    for (auto &e : entries)  // to the block's numbering
      e = Eigen::Triplet<double>(local[e.row()], local[e.col()], e.value());
    for (std::size_t a = 0; a < touched_.size(); ++a)
      entries.emplace_back(a, a, sigma);
    const Eigen::Index          m = Eigen::Index(touched_.size());
    Eigen::SparseMatrix<double> block(m, m);
    block.setFromTriplets(entries.begin(), entries.end());
    block_.compute(block);
    if (block_.info() != Eigen::Success)
      throw std::runtime_error("the outer preconditioner is not positive definite");
  }

  Eigen::VectorXd ShiftedSparseInverse::solve(const Eigen::VectorXd &v) const
  {
    Eigen::VectorXd z = v / sigma_;
    if (touched_.empty())
      return z;
    Eigen::VectorXd local(touched_.size());
    for (std::size_t a = 0; a < touched_.size(); ++a)
      local[a] = v[touched_[a]];
    local = block_.solve(local);
    for (std::size_t a = 0; a < touched_.size(); ++a)
      z[touched_[a]] = local[a];
    return z;
  }
} // namespace ritr
