#pragma once
// The model of one outer trust-region iteration and the step it proposes. The model is
//   m(p) = (g - g_b).p + 1/2 p.(S - H_b) p + b(u + B p) - b(u)   in the sliding basis,
// with S the exact reduced Hessian (reduced_hessian.h) or its quasi-Newton approximation
// (quasi_newton_curvature.h) and b the reference measure barrier,
// whose gradient g_b and Hessian H_b at u are part of g and S: quadratic in the rest of R,
// exact in the barrier (measure_barrier_model.h). A quadratic barrier model sent CG steps into the
// barrier, and cutting them to their best fraction made most of the bar's steps at epsilon r
// 1e-6 short (462 of 592 cut, ratios near 1): the outer solve crawled along the barrier.
// The step minimises m by a few Newton iterations of the model itself, each a Steihaug CG on
// S - H_b + H_b(u + B p) plus the barrier's secants (measure_barrier_model.h) in the norm of
// M = sigma I + H_b(u + B p) + secants, sigma the model's curvature along the gradient (the
// barrier makes a few cells orders stiffer than the rest, and without M CG ran into its
// iteration limit). The region is a ball in the norm of M at u, fixed during a proposal;
// lengths |p|_M / sigma^1/2 are Euclidean lengths for steps that move no cell near the
// barrier, so that radii are lengths.
#include <ritr/adaptivity/measure_barrier_model.h>
#include <ritr/adaptivity/outer_curvature.h>
#include <ritr/solver/shifted_sparse_inverse.h>

#include <functional>

namespace ritr
{
  template <int dim>
  class OuterModel
  {
  public:
    // `g` in basis coordinates.
    OuterModel(const OuterCurvature &hessian, const Eigen::VectorXd &g, const Eigen::SparseMatrix<double> &basis);

    struct Step
    {
      Eigen::VectorXd p, du;  // basis and reference coordinates
      double       predicted = 0;  // the model's change along p, with the barrier's actual change
      bool         newton    = false;  // the model's minimum inside the region (a Newton step)
      bool         converged = false;  // a Newton step below epsilon_r (returned uncut)
    };

    // The largest admissible fraction of the reference step ddu taken after du.
    using StepFilter = std::function<double(const Eigen::VectorXd &du, const Eigen::VectorXd &ddu)>;

    // Newton iterations on the model inside the region of the given length (at most 8), each
    // a CG to the residual `forcing` |g| and a step cut to its best fraction under
    // `step_filter` and the exact barrier, until the model's gradient falls below `forcing`
    // |g|; a direction the barrier cuts to less than half gets secants and CG again (at most
    // three times per proposal). A later CG starts from the rest of the cut direction (after a
    // cut) or from its cut part (after secants) when that guess leaves a smaller residual than
    // the gradient. A first Newton step below `epsilon_r` is returned uncut, after a tight CG
    // from zero confirmed it (a loose residual may hide soft directions behind a stiff one).
    Step propose(double radius, double forcing, double epsilon_r, const StepFilter &step_filter,
                 MeasureBarrierModel<dim> &barrier);

    // The length of a step of the last proposal (in its region's norm).
    double length(const Eigen::VectorXd &p) const;

  private:
    // sigma I + a barrier Hessian.
    Eigen::SparseMatrix<double> metric(const Eigen::SparseMatrix<double> &barrier_hessian) const;

    const OuterCurvature              &hessian_;
    const Eigen::VectorXd             &g_;
    const Eigen::SparseMatrix<double> &basis_;
    ShiftedSparseInverse               preconditioner_;  // CG's, the inverse of a metric
    double                             sigma_ = 0;
    Eigen::SparseMatrix<double>        metric_;  // the region's norm, at u, set by propose
  };
} // namespace ritr
