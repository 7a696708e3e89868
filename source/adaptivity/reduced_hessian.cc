#include <ritr/adaptivity/reduced_hessian.h>
#include <ritr/common/symmetric_product.h>

namespace ritr
{
  ReducedHessian::ReducedHessian(const Triplets &huu, const Triplets &hxx, const Triplets &hxu, const Eigen::Index n_z,
                                 const std::vector<int> &free_state, const Eigen::SparseMatrix<double> &basis,
                                 SparseCholesky &cholesky, const Eigen::Index dense_limit)
    : free_state_(free_state)
    , n_z_(n_z)
    , cholesky_(cholesky)
  {
    const Eigen::Index n_u = basis.rows(), n_f = free_state.size();
    std::vector<int>   free_index(n_z, -1);
    for (Eigen::Index a = 0; a < n_f; ++a)
      free_index[free_state[a]] = a;

    Eigen::SparseMatrix<double> h(n_u, n_u);
    h.setFromTriplets(huu.begin(), huu.end());
    huu_ = basis.transpose() * h * basis;

    Triplets free_xx, free_xu;
    for (const auto &t : hxx)
      {
        const int r = free_index[t.row()], c = free_index[t.col()];
        if (r >= 0 && c >= 0 && r >= c)
          free_xx.emplace_back(r, c, t.value());
      }
    for (const auto &t : hxu)
      if (free_index[t.row()] >= 0)
        free_xu.emplace_back(free_index[t.row()], t.col(), t.value());
    Eigen::SparseMatrix<double> xx(n_f, n_f), xu(n_f, n_u);
    xx.setFromTriplets(free_xx.begin(), free_xx.end());
    xx.makeCompressed();
    xu.setFromTriplets(free_xu.begin(), free_xu.end());
    coupling_ = xu * basis;
    shift_    = cholesky_.factorize(xx);
    if (basis.cols() <= dense_limit)
      {
        const Eigen::MatrixXd response = cholesky_.solve_columns(Eigen::MatrixXd(coupling_));
        dense_                         = Eigen::MatrixXd(huu_) - coupling_.transpose() * response;
        dense_                         = 0.5 * (dense_ + dense_.transpose()).eval();  // symmetric to round-off
      }
  }

  Eigen::VectorXd ReducedHessian::apply(const Eigen::VectorXd &p) const
  {
    if (dense())
      return symmetric_product(dense_, p);
    const Eigen::VectorXd response = cholesky_.solve(coupling_ * p);  // -dx on the free state
    return huu_ * p - coupling_.transpose() * response;
  }

  Eigen::VectorXd ReducedHessian::state_response(const Eigen::VectorXd &p) const
  {
    const Eigen::VectorXd response = cholesky_.solve(coupling_ * p);
    Eigen::VectorXd       dz       = Eigen::VectorXd::Zero(n_z_);
    for (std::size_t a = 0; a < free_state_.size(); ++a)
      dz[free_state_[a]] = -response[a];
    return dz;
  }

  void fold_following_prescribed(const std::vector<int> &entries, const Eigen::VectorXd &gx, const Triplets &hxx,
                                 Eigen::VectorXd &gu, Triplets &huu, Triplets &hxu)
  {
    if (entries.empty())
      return;
    std::vector<bool> follows(gx.size(), false);
    for (const int e : entries)
      {
        follows[e] = true;
        gu[e] += gx[e];
      }
    const std::size_t n_coupling = hxu.size();
    for (std::size_t i = 0; i < n_coupling; ++i)
      if (follows[hxu[i].row()])
        {
          const auto t = hxu[i];  // emplace_back may move hxu's storage: copy first
          huu.emplace_back(t.row(), t.col(), t.value());
          huu.emplace_back(t.col(), t.row(), t.value());
        }
    for (const auto &t : hxx)
      if (follows[t.col()])
        {
          if (follows[t.row()])
            huu.emplace_back(t.row(), t.col(), t.value());
          else
            hxu.emplace_back(t.row(), t.col(), t.value());
        }
  }
} // namespace ritr
