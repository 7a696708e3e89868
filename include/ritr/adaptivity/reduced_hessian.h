#pragma once
// The exact Hessian of u -> R(x(u), u) with x(u) = argmin E(., u), in the sliding basis B:
//
//   S = B^T (H_uu - H_xu^T H_xx^-1 H_xu) B      (H_xx, H_xu restricted to the free state)
//
// One sparse Cholesky factorization of H_xx per outer iteration. Up to `dense_limit` reference
// unknowns S is then formed once, with one blocked solve for all its columns, and applied as a
// dense matrix: the outer model applies S hundreds of times per outer iteration, and a single
// back-substitution costs more in CHOLMOD's and BLAS's per-call overhead than in arithmetic
// (the 209-vertex ball: ~80 us per CG iteration, ~100 iterations per CG). Larger problems
// apply it matrix-free, a back-substitution per product: a dense product reads n^2 numbers, and
// on the masticator's ~840 and ~1,250 unknowns an outer iteration took 1.6x and 3.8x as long
// dense as matrix-free, hence the limit of 500. The same factor gives the
// implicit-function response of x, dx = -H_xx^-1 H_xu B p, which predicts the state at a
// trial mesh.
#include <ritr/adaptivity/outer_curvature.h>
#include <ritr/solver/newton.h>
#include <ritr/solver/sparse_cholesky.h>

#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  class ReducedHessian : public OuterCurvature
  {
  public:
    // Blocks as assembled by TermSum::reference_derivatives (state numbering for x, n_z entries;
    // reference numbering for u, basis.rows() entries); `free_state` lists the state entries
    // that are not prescribed. Reuses `cholesky`'s symbolic analysis while the pattern holds.
    ReducedHessian(const Triplets &huu, const Triplets &hxx, const Triplets &hxu, Eigen::Index n_z,
                   const std::vector<int> &free_state, const Eigen::SparseMatrix<double> &basis,
                   SparseCholesky &cholesky, Eigen::Index dense_limit = 500);

    // S p for p in basis coordinates.
    Eigen::VectorXd apply(const Eigen::VectorXd &p) const override;
    // The first-order change of the whole state z for the reference step B p (prescribed
    // entries do not move).
    Eigen::VectorXd state_response(const Eigen::VectorXd &p) const;
    // Multiple of the identity that had to be added to H_xx (0: it was positive definite).
    double state_shift() const { return shift_; }
    // Whether S was formed densely.
    bool dense() const { return dense_.size() > 0; }

  private:
    Eigen::SparseMatrix<double> huu_;       // B^T H_uu B
    Eigen::SparseMatrix<double> coupling_;  // H_xu B on the free state rows
    Eigen::MatrixXd             dense_;     // S, when formed
    const std::vector<int>     &free_state_;
    Eigen::Index                n_z_;
    SparseCholesky             &cholesky_;
    double                      shift_ = 0;
  };

  // Prescribed state entries p whose targets follow u (x_p = u_p + a constant; state and
  // reference share the body's numbering): the composition R(x_f, x_p(u), u) has the gradient
  // g_u + g_p, the Hessian H_uu + H_pu + H_up + H_pp and the coupling H_fu + H_fp. Folds the
  // blocks (hxx with both triangles, as assembled) so that ReducedHessian and B^T g_u are
  // those of the composition.
  void fold_following_prescribed(const std::vector<int> &entries, const Eigen::VectorXd &gx, const Triplets &hxx,
                                 Eigen::VectorXd &gu, Triplets &huu, Triplets &hxu);
} // namespace ritr
