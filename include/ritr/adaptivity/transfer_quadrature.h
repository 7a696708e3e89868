#pragma once
// The high-order simplex rules the L2 transfer integrates with: deal.II's Witherden-Vincent
// rules (the paper's choice), converted to barycentric points on the unit simplex.
#include <ritr/transfer/simplex_quadrature.h>

namespace ritr
{
  // n_points_1d as for deal.II's QWitherdenVincentSimplex (Gauss-Legendre in 1D).
  template <int dim>
  transfer::SimplexQuadrature<dim> witherden_vincent_rule(unsigned int n_points_1d);
} // namespace ritr
