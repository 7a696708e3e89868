#pragma once
// deal.II's quadrature rules on the unit simplex, converted to barycentric points (the form
// the element kernels and the L2 transfer take): Gauss rules for the mass matrix and the
// Witherden-Vincent rules (the paper's choice) for the transfer's piecewise integrands.
#include <ritr/common/simplex_quadrature.h>

namespace ritr
{
  // n_points_1d as for deal.II's QGaussSimplex (QGauss in 1D).
  template <int dim>
  SimplexQuadrature<dim> gauss_simplex_rule(unsigned int n_points_1d);

  // n_points_1d as for deal.II's QWitherdenVincentSimplex (QGauss in 1D).
  template <int dim>
  SimplexQuadrature<dim> witherden_vincent_rule(unsigned int n_points_1d);
} // namespace ritr
