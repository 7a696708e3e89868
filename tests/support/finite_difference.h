#pragma once
// Central finite differences of scalar and vector functions, for derivative checks.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <functional>
#include <vector>

namespace ritr::test_support
{
  inline Eigen::VectorXd fd_gradient(const std::function<double(const Eigen::VectorXd &)> &f,
                                     const Eigen::VectorXd &x, const double step)
  {
    Eigen::VectorXd g(x.size());
    Eigen::VectorXd y = x;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      {
        y[i]       = x[i] + step;
        const double fp = f(y);
        y[i]       = x[i] - step;
        const double fm = f(y);
        y[i]       = x[i];
        g[i]       = (fp - fm) / (2 * step);
      }
    return g;
  }

  // Jacobian of a vector function, column i = d f / d x_i.
  inline Eigen::MatrixXd fd_jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd &)> &f,
                                     const Eigen::VectorXd &x, const double step)
  {
    Eigen::VectorXd y = x;
    Eigen::MatrixXd j;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      {
        y[i]                   = x[i] + step;
        const Eigen::VectorXd fp = f(y);
        y[i]                   = x[i] - step;
        const Eigen::VectorXd fm = f(y);
        y[i]                   = x[i];
        if (i == 0)
          j.resize(fp.size(), x.size());
        j.col(i) = (fp - fm) / (2 * step);
      }
    return j;
  }

  // A dense matrix from triplets (duplicates summed), to compare with differences.
  inline Eigen::MatrixXd dense(const std::vector<Eigen::Triplet<double>> &t, const Eigen::Index rows,
                               const Eigen::Index cols)
  {
    Eigen::SparseMatrix<double> s(rows, cols);
    s.setFromTriplets(t.begin(), t.end());
    return Eigen::MatrixXd(s);
  }

  // Relative error that is meaningful for both large and near-zero quantities.
  inline double relative_error(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b)
  {
    return (a - b).norm() / std::max({a.norm(), b.norm(), 1e-12});
  }
} // namespace ritr::test_support
