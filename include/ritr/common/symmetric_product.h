#pragma once
// y = A p for a dense symmetric A, reading A's lower triangle only, by BLAS's dsymv.
//
// The outer model applies its dense reduced Hessian (a few hundred unknowns) some hundreds of
// times per outer iteration. Eigen's product, compiled for the baseline instruction set, reads
// the whole matrix; the system BLAS (OpenBLAS, its kernels chosen for the CPU at run time)
// reads half of it with wider instructions: on the ball's 370 unknowns 8-10 us a product
// against 18-30 us.
#include <Eigen/Core>

namespace ritr
{
  // `lower`'s lower triangle is A; the strict upper triangle is not read.
  Eigen::VectorXd symmetric_product(const Eigen::MatrixXd &lower, const Eigen::VectorXd &p);
} // namespace ritr
