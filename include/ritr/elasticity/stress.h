#pragma once
// Stress for the outputs: the Cauchy (true) stress sigma = P F^T / J of a material at a
// deformation gradient, and its von Mises equivalent, the scalar users colour by.
#include <ritr/elasticity/cell_materials.h>

#include <vector>

namespace ritr
{
  // The 3 x 3 Cauchy stress at the deformation gradient F. 2D is plane strain: F is embedded
  // with F_zz = 1, so sigma_zz is the stress that keeps the thickness fixed. A 1D rod is in
  // uniaxial stress: only sigma_xx = P (its cross-section is not modelled, so J = F).
  template <int dim>
  SmallMatrix<3, double> cauchy_stress(const Material &material, const SmallMatrix<dim, double> &F);

  // sqrt(3/2 s:s) with s the deviatoric part of sigma.
  double von_mises(const SmallMatrix<3, double> &sigma);

  // Von Mises stress of every cell of the deformation u -> x.
  template <int dim>
  std::vector<double> cell_von_mises_stresses(const CellMaterials<dim> &materials, const Eigen::VectorXd &x,
                                              const Eigen::VectorXd &u);
} // namespace ritr
