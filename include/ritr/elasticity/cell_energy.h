#pragma once
// The part of the incremental potential that lives on cells (paper eqs. 6 and 10): corrected
// inertia 1/2 x^T M(u) x - x^T M(u) x_pred, plus the weighted potential energy
// h^2 (Psi(x,u) - gravity work). Written once as a template on the scalar type: doubles for
// values, SecondOrderDual over (x_e, u_e) for the joint derivatives that r-adaptivity and the
// finite-difference tests need.
#include <ritr/common/second_order_dual.h>
#include <ritr/common/small_matrix.h>
#include <ritr/elasticity/material.h>

#include <array>

namespace ritr
{
  template <int dim, typename Scalar>
  using CellNodes = std::array<std::array<Scalar, dim>, dim + 1>;

  template <int dim>
  struct CellEnergyWeights
  {
    double                     inertia   = 1.0;  // 1 for dynamics, 0 for statics
    double                     potential = 1.0;  // h^2 for dynamics, 1 for statics
    std::array<double, dim>    gravity{};        // acceleration, already load-scaled
    // Uncorrected inertia (paper eq. 8) adds 1/2 x_pred^T M x_pred; kept only to show its bias.
    bool                       corrected_inertia = true;
  };

  // Consistent P1 mass matrix of the reference simplex divided by its measure:
  // int lambda_a lambda_b / |T|, computed with deal.II's simplex quadrature.
  template <int dim>
  const std::array<std::array<double, dim + 1>, dim + 1> &unit_mass_coefficients();

  // Deformation gradient F = Ds(x) Dm(u)^{-1} of a P1 simplex.
  template <int dim, typename Scalar>
  SmallMatrix<dim, Scalar> deformation_gradient(const CellNodes<dim, Scalar> &x,
                                                const CellNodes<dim, Scalar> &u)
  {
    return multiply<dim, Scalar>(edge_matrix<dim, Scalar>(x),
                                 inverse<dim, Scalar>(edge_matrix<dim, Scalar>(u)));
  }

  template <int dim, typename Scalar>
  Scalar cell_energy(const Material &material, const CellEnergyWeights<dim> &w,
                     const CellNodes<dim, Scalar> &x, const CellNodes<dim, Scalar> &u,
                     const CellNodes<dim, double> &x_pred)
  {
    const Scalar measure = simplex_measure<dim, Scalar>(u);
    const auto  &mass    = unit_mass_coefficients<dim>();
    Scalar       energy(0.0);
    if (w.inertia != 0.0)
      {
        Scalar kinetic(0.0);
        for (int a = 0; a <= dim; ++a)
          for (int b = 0; b <= dim; ++b)
            for (int k = 0; k < dim; ++k)
              {
                Scalar term = 0.5 * x[a][k] * x[b][k] - x[a][k] * x_pred[b][k];
                if (!w.corrected_inertia)
                  term = term + 0.5 * x_pred[a][k] * x_pred[b][k];
                kinetic = kinetic + mass[a][b] * term;
              }
        energy = energy + w.inertia * material.density * measure * kinetic;
      }
    Scalar work(0.0);
    for (int a = 0; a <= dim; ++a)
      for (int k = 0; k < dim; ++k)
        work = work + x[a][k] * w.gravity[k];
    const Scalar potential =
      measure * (strain_energy_density<dim, Scalar>(material, deformation_gradient<dim, Scalar>(x, u)) -
                 material.density / (dim + 1) * work);
    return energy + w.potential * potential;
  }
} // namespace ritr
