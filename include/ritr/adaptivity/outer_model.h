#pragma once
// The model of one outer trust-region iteration and the step it proposes. The model is
//   m(p) = g.p + 1/2 p.(S + secants) p   in the sliding basis,
// with S the exact reduced Hessian (reduced_hessian.h) and the secant curvature of cells the
// measure barrier cut short (measure_barrier_model.h). Steps are Steihaug CG in the norm of
// the preconditioner M = sigma I + (barrier Hessian and secants), sigma the model's
// curvature along the gradient: secants make a few cells orders stiffer than the rest, and
// without it CG ran into its iteration limit (3,180 products on the bar). Lengths |p|_M / sigma^1/2 are
// Euclidean lengths for steps that move no cell near the barrier, so that radii are lengths.
#include <ritr/adaptivity/measure_barrier_model.h>
#include <ritr/adaptivity/reduced_hessian.h>

#include <functional>

namespace ritr
{
  template <int dim>
  class OuterModel
  {
  public:
    // `g` in basis coordinates; `preconditioner` keeps its symbolic analysis across iterations.
    OuterModel(const ReducedHessian &hessian, const MeasureBarrierModel<dim> &barrier, const Eigen::VectorXd &g,
               const Eigen::SparseMatrix<double> &basis, SparseCholesky &preconditioner);

    struct Step
    {
      Eigen::VectorXd p, du;  // basis and reference coordinates
      double       predicted = 0;  // the model's change along p, with the barrier's actual change
      bool         newton    = false;  // CG converged inside the region: a Newton step
      bool         converged = false;  // a Newton step below epsilon_r (returned uncut)
    };

    // A CG step in the region of the given length (residual `forcing` |g|) on the model, then
    // cut to its best fraction under `step_filter` (the largest admissible fraction of a
    // reference step) and the exact barrier; while the barrier cuts it to less than half, the
    // cut cells get secants (in `barrier`) and CG runs again, at most three times. A Newton
    // step below `epsilon_r` is returned uncut, after a tight CG confirmed it (a loose
    // residual may hide soft directions behind a stiff one).
    Step propose(double radius, double forcing, double epsilon_r,
                 const std::function<double(const Eigen::VectorXd &)> &step_filter,
                 MeasureBarrierModel<dim> &barrier);

    double length(const Eigen::VectorXd &p) const;

  private:
    void build_preconditioner(const MeasureBarrierModel<dim> &barrier);

    const ReducedHessian              &hessian_;
    const Eigen::VectorXd             &g_;
    const Eigen::SparseMatrix<double> &basis_;
    SparseCholesky                    &preconditioner_;
    double                             sigma_ = 0;
    Eigen::SparseMatrix<double>        metric_;
  };
} // namespace ritr
