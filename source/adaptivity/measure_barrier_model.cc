#include <ritr/adaptivity/measure_barrier_model.h>
#include <ritr/common/log_barrier.h>
#include <ritr/common/simplex_measure.h>
#include <ritr/common/small_matrix.h>

#include <cmath>
#include <limits>

namespace ritr
{
  template <int dim>
  MeasureBarrierModel<dim>::MeasureBarrierModel(const SimplexMesh<dim> &mesh, const Eigen::SparseMatrix<double> &basis,
                                                const double w_hat, const double kappa)
    : mesh_(mesh)
    , basis_(basis)
    , w_hat_(w_hat)
    , kappa_(kappa)
    , secant_(mesh.n_cells(), 0.0)
  {}

  template <int dim>
  double MeasureBarrierModel<dim>::value_at(const Eigen::VectorXd &u) const
  {
    return kappa_ > 0 ? reference_measure_barrier(mesh_, u, w_hat_, kappa_) : 0.0;
  }

  template <int dim>
  void MeasureBarrierModel<dim>::set_point(const Eigen::VectorXd &u)
  {
    u_    = u;
    base_ = at(Eigen::VectorXd::Zero(basis_.cols()));
    build_secant_rows();
  }

  template <int dim>
  void MeasureBarrierModel<dim>::build_secant_rows()
  {
    constexpr int n = dim * (dim + 1);
    Triplets      rows;
    for (unsigned int c = 0; c < secant_.size(); ++c)
      if (secant_[c] > 0)
        {
          const auto &cell    = mesh_.cells[c];
          const auto  measure = cell_measure_derivatives<dim>(u_, cell);
          for (int i = 0; i < n; ++i)
            rows.emplace_back(c, cell[i / dim] * dim + i % dim, std::sqrt(secant_[c]) * measure.grad[i]);
        }
    Eigen::SparseMatrix<double> rows_u(secant_.size(), u_.size());
    rows_u.setFromTriplets(rows.begin(), rows.end());
    secant_rows_ = rows_u * basis_;
  }

  template <int dim>
  Eigen::SparseMatrix<double> MeasureBarrierModel<dim>::secants() const
  {
    return secant_rows_.transpose() * secant_rows_;
  }

  template <int dim>
  bool MeasureBarrierModel<dim>::add_secants(const Eigen::VectorXd &p, const Eigen::VectorXd &d)
  {
    if (kappa_ <= 0)
      return false;
    const Eigen::VectorXd u0 = u_ + basis_ * p, u1 = u0 + basis_ * d;
    bool                  added = false;
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      {
        const double w0 = simplex_measure<dim, double>(cell_nodes<dim>(u0, mesh_.cells[c]));
        const double w1 = simplex_measure<dim, double>(cell_nodes<dim>(u1, mesh_.cells[c]));
        if (!(w1 < w_hat_ && w1 < w0 && w1 > 0))
          continue;
        const double dw = w1 - w0;
        const double b0 = w0 < w_hat_ ? log_barrier(w0, w_hat_) : 0.0;
        const double d0 = w0 < w_hat_ ? log_barrier_derivative(w0, w_hat_) : 0.0;
        const double h0 = w0 < w_hat_ ? log_barrier_second_derivative(w0, w_hat_) : 0.0;
        // Curvature of the secant quadratic through (w0, b0) with slope d0 and (w1, b1),
        // beyond what the Hessian at w0 already holds.
        const double extra = kappa_ * (2 * (log_barrier(w1, w_hat_) - b0 - d0 * dw) / (dw * dw) - h0);
        if (extra > secant_[c])
          {
            secant_[c] = extra;
            added      = true;
          }
      }
    if (added)
      build_secant_rows();
    return added;
  }

  template <int dim>
  typename MeasureBarrierModel<dim>::Derivatives MeasureBarrierModel<dim>::at(const Eigen::VectorXd &p) const
  {
    const Eigen::VectorXd u = u_ + basis_ * p;
    Eigen::VectorXd       g = Eigen::VectorXd::Zero(u.size());
    Triplets              h;
    Derivatives           d;
    d.value = kappa_ > 0 ? reference_measure_barrier(mesh_, u, w_hat_, kappa_, &g, &h, true) : 0.0;
    Eigen::SparseMatrix<double> full(u.size(), u.size());
    full.setFromTriplets(h.begin(), h.end());
    d.gradient = basis_.transpose() * g;
    d.hessian  = basis_.transpose() * full * basis_;
    return d;
  }

  template <int dim>
  std::pair<double, double> MeasureBarrierModel<dim>::best_fraction(const Eigen::VectorXd &p, const Eigen::VectorXd &d,
                                                                    const double value_at_p, const double alpha_max,
                                                                    const double slope, const double curvature) const
  {
    const Eigen::VectorXd     u = u_ + basis_ * p, du = basis_ * d;
    std::pair<double, double> best{alpha_max, std::numeric_limits<double>::infinity()};
    // Uniform fractions, then halvings down to 2^-40: a cell at the barrier's onset may only
    // admit a tiny step along a direction that ignores it.
    constexpr int uniform = 32, halvings = 40;
    for (int k = 0; k < uniform + halvings; ++k)
      {
        const double alpha =
          alpha_max * (k < uniform ? double(uniform - k) / uniform : std::ldexp(1.0, -(k - uniform + 6)));
        double change = alpha * slope + 0.5 * alpha * alpha * curvature;
        if (kappa_ > 0)
          change += value_at(Eigen::VectorXd(u + alpha * du)) - value_at_p;
        if (change < best.second)
          best = {alpha, change};
      }
    return best;
  }

  template class MeasureBarrierModel<1>;
  template class MeasureBarrierModel<2>;
  template class MeasureBarrierModel<3>;
} // namespace ritr
