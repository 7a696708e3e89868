#include <ritr/common/log_barrier.h>
#include <ritr/common/psd_projection.h>
#include <ritr/common/simplex_measure.h>
#include <ritr/terms/measure_barrier_term.h>

#include <algorithm>
#include <limits>

namespace ritr
{
  template <int dim>
  double reference_measure_barrier(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &u, const double w_hat,
                                   const double kappa, Eigen::VectorXd *gradient, Triplets *hessian,
                                   const bool project_psd)
  {
    constexpr int n      = dim * (dim + 1);
    double        energy = 0;
    for (const auto &cell : mesh.cells)
      {
        const double w = simplex_measure<dim, double>(cell_nodes<dim>(u, cell));
        if (w >= w_hat)
          continue;
        if (w <= 0)
          return std::numeric_limits<double>::infinity();
        energy += kappa * log_barrier(w, w_hat);
        if (!gradient && !hessian)
          continue;
        const auto   measure = cell_measure_derivatives<dim>(u, cell);
        const double db      = log_barrier_derivative(w, w_hat);
        const double d2b     = log_barrier_second_derivative(w, w_hat);
        if (gradient)
          for (int i = 0; i < n; ++i)
            (*gradient)[cell[i / dim] * dim + i % dim] += kappa * db * measure.grad[i];
        if (hessian)
          {
            Eigen::Matrix<double, n, n> block = kappa * (d2b * measure.grad * measure.grad.transpose() + db * measure.hess);
            if (project_psd)
              block = project_to_psd(block);
            for (int i = 0; i < n; ++i)
              for (int j = 0; j < n; ++j)
                hessian->emplace_back(cell[i / dim] * dim + i % dim, cell[j / dim] * dim + j % dim, block(i, j));
          }
      }
    return energy;
  }

  template <int dim>
  MeasureBarrierTerm<dim>::MeasureBarrierTerm(const SimplexMesh<dim> &mesh)
    : mesh_(mesh)
  {
    w_hat_ = std::numeric_limits<double>::max();
    for (const auto &cell : mesh.cells)
      w_hat_ = std::min(w_hat_, 0.1 * simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell)));
  }

  template <int dim>
  double MeasureBarrierTerm<dim>::value(const TermPoint &p) const
  {
    return kappa_ > 0 ? reference_measure_barrier(mesh_, p.u, w_hat_, kappa_) : 0.0;
  }

  template <int dim>
  void MeasureBarrierTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock, const bool,
                                                          ReferenceDerivativeAssembly<dim> &d) const
  {
    if (kappa_ > 0)
      reference_measure_barrier(mesh_, p.u, w_hat_, kappa_, &d.gu, &d.huu.triplets(), true);
  }

#define RITR_INSTANTIATE(dim)                                                                                          \
  template double reference_measure_barrier<dim>(const SimplexMesh<dim> &, const Eigen::VectorXd &, double, double,    \
                                                 Eigen::VectorXd *, Triplets *, bool);                                 \
  template class MeasureBarrierTerm<dim>;
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
