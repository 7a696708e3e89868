#pragma once
// The joint derivatives of a cell term f(x, u) = |T(u)| q(x) whose x-part q is a polynomial of
// degree at most two in the cell's node positions (inertia, body forces): with m = |T| and
// its derivatives (common/simplex_measure.h),
//   f_x = m q_x,  f_u = q m_u,  f_xx = m q_xx,  f_xu = q_x m_u^T,  f_uu = q m_uu,
// added for cell c into the outer solve's assembly; or f_u alone into g_u. Not thread-safe
// (gradients scatter).
#include <ritr/common/simplex_measure.h>
#include <ritr/terms/energy_term.h>

namespace ritr
{
  template <int dim>
  void add_measure_weighted_cell(const std::size_t c, const std::array<unsigned int, dim + 1> &cell, const double q,
                                 const Eigen::Matrix<double, dim *(dim + 1), 1>                &q_x,
                                 const Eigen::Matrix<double, dim *(dim + 1), dim *(dim + 1)> &q_xx,
                                 const SecondOrderDual<dim *(dim + 1)> &measure, const ReferenceBlock block,
                                 const bool coupling, ReferenceDerivativeAssembly<dim> &d)
  {
    constexpr int n  = dim * (dim + 1);
    const double  m  = measure.value;
    const Eigen::Matrix<double, n, n> f_xu = q_x * measure.grad.transpose();
    auto huu = d.huu.cell_block(c);
    huu += q * measure.hess;
    if (block == ReferenceBlock::following)
      huu += m * q_xx + f_xu + f_xu.transpose();
    if (coupling)
      {
        d.hxx.cell_block(c) += m * q_xx;
        d.hxu.cell_block(c) += f_xu;
      }
    for (int i = 0; i < n; ++i)
      {
        const unsigned int dof = cell[i / dim] * dim + i % dim;
        d.gu[dof] += q * measure.grad[i];
        if (coupling)
          d.gx[dof] += m * q_x[i];
      }
  }

  template <int dim>
  void add_measure_weighted_gradient(const std::array<unsigned int, dim + 1> &cell, const double q,
                                     const FirstOrderDual<dim *(dim + 1)> &measure, Eigen::VectorXd &gu)
  {
    for (int i = 0; i < dim * (dim + 1); ++i)
      gu[cell[i / dim] * dim + i % dim] += q * measure.grad[i];
  }
} // namespace ritr
