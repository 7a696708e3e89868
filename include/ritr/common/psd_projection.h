#pragma once
// Projection of a small symmetric matrix onto the positive semi-definite cone, by clamping
// negative eigenvalues to zero. Projected Newton applies it per element / per contact
// stencil so that the assembled Hessian is positive semi-definite.
#include <Eigen/Eigenvalues>

namespace ritr
{
  template <typename Matrix>
  Matrix project_to_psd(const Matrix &m)
  {
    Eigen::SelfAdjointEigenSolver<Matrix> eig(0.5 * (m + m.transpose()));
    auto values = eig.eigenvalues();
    if (values.minCoeff() >= 0.0)
      return 0.5 * (m + m.transpose());
    for (Eigen::Index i = 0; i < values.size(); ++i)
      values[i] = values[i] > 0.0 ? values[i] : 0.0;
    return eig.eigenvectors() * values.asDiagonal() * eig.eigenvectors().transpose();
  }
} // namespace ritr
