#pragma once
// d2Psi/dF2 of a material, flattened row-major (F_kj at k * dim + j), and the change that
// projects it onto the positive semi-definite cone, which projected Newton applies per cell
// (the map F -> x is linear, so a PSD density Hessian gives a PSD element block).
//
// The projection uses the analytic eigensystem of isotropic energies (Smith, de Goes and Kim,
// "Analytic eigensystems for isotropic distortion energies", 2019): with the signed SVD
// F = U diag(s) V^T, the eigenvectors are U D V^T for
//   - the dim "scaling" modes, D = diag(a) for the eigenvectors a of d2Psi/ds2;
//   - one "twist" (D = (e_i e_j^T - e_j e_i^T)/sqrt 2) and one "flip" (D = (e_i e_j^T +
//     e_j e_i^T)/sqrt 2) per pair i < j, with eigenvalues (Psi_i + Psi_j)/(s_i + s_j) and
//     (Psi_i - Psi_j)/(s_i - s_j), which the models below give in closed form (no division by
//     s_i - s_j).
// A small SVD replaces the eigendecomposition of the dim^2 x dim^2 matrix, which was the
// largest single cost of a Newton iteration on compressed meshes (most cells of an impact
// are indefinite: neo-Hookean's twist mode is negative in compression).
#include <ritr/common/small_matrix.h>
#include <ritr/elasticity/material.h>

#include <Eigen/Core>

#include <optional>

namespace ritr
{
  template <int dim>
  using DensityHessian = Eigen::Matrix<double, dim * dim, dim * dim>;

  // d2Psi/dF2: neo-Hookean in closed form, the other models through dual numbers.
  template <int dim>
  DensityHessian<dim> energy_density_hessian(const Material &material, const SmallMatrix<dim, double> &F);

  // What to add to `hessian` (= energy_density_hessian at F) to clamp its negative
  // eigenvalues to zero; nothing where it is already positive definite (then no SVD is
  // computed) or semi-definite, as the linear model always is.
  template <int dim>
  std::optional<DensityHessian<dim>> density_hessian_projection(const Material &material, const SmallMatrix<dim, double> &F,
                                                                const DensityHessian<dim> &hessian);
} // namespace ritr
