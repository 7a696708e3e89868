#pragma once
// Kernels of the cell terms on one P1 simplex, written once as templates on the scalar type
// (doubles for values, SecondOrderDual over (x_e, u_e) for the joint derivatives that
// r-adaptivity and the finite-difference tests need): the deformation gradient, the strain
// energy |T(u)| Psi(F) and the consistent mass coefficients.
#include <ritr/common/second_order_dual.h>
#include <ritr/common/small_matrix.h>
#include <ritr/elasticity/material.h>

#include <array>

namespace ritr
{
  template <int dim, typename Scalar>
  using CellNodes = std::array<std::array<Scalar, dim>, dim + 1>;

  // Consistent P1 mass matrix of the reference simplex divided by its measure:
  // int lambda_a lambda_b / |T|, computed with deal.II's simplex quadrature.
  template <int dim>
  const std::array<std::array<double, dim + 1>, dim + 1> &unit_mass_coefficients();

  // Deformation gradient F = Ds(x) Dm(u)^{-1} of a P1 simplex.
  template <int dim, typename Scalar>
  SmallMatrix<dim, Scalar> deformation_gradient(const CellNodes<dim, Scalar> &x, const CellNodes<dim, Scalar> &u)
  {
    return multiply<dim, Scalar>(edge_matrix<dim, Scalar>(x), inverse<dim, Scalar>(edge_matrix<dim, Scalar>(u)));
  }

  // |T(u)| Psi(F(x, u)): the cell's strain energy (+infinity for an inverted neo-Hookean cell).
  template <int dim, typename Scalar>
  Scalar strain_energy(const Material &material, const CellNodes<dim, Scalar> &x, const CellNodes<dim, Scalar> &u)
  {
    return simplex_measure<dim, Scalar>(u) *
           strain_energy_density<dim, Scalar>(material, deformation_gradient<dim, Scalar>(x, u));
  }
} // namespace ritr
