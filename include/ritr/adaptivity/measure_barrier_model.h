#pragma once
// The reference measure barrier (eq. 21) inside the outer trust-region model. The barrier is
// C2 at its threshold w_hat and then grows like kappa (w_hat - w)^3 / w_hat with the contact
// stiffness kappa: a quadratic model taken at a cell outside (or just inside) the threshold
// has no curvature there and proposes steps that drive the cell deep into it. Two remedies,
// both cheap because the barrier depends on u alone (one pass over the cells):
//  - along a step the model takes the barrier's actual change (best_fraction);
//  - a cell that a step drove into the barrier gets the secant curvature of the barrier over
//    that step, kappa_c grad w grad w^T, added to the model Hessian for the rest of the time
//    step (add_secants / apply), so that the next step stops where the barrier balances.
#include <ritr/terms/measure_barrier_term.h>

#include <Eigen/Sparse>

#include <utility>
#include <vector>

namespace ritr
{
  template <int dim>
  class MeasureBarrierModel
  {
  public:
    // `basis` maps step coordinates to reference entries (ritr_solver.h); kappa 0: no barrier.
    MeasureBarrierModel(const SimplexMesh<dim> &mesh, const Eigen::SparseMatrix<double> &basis, double w_hat,
                        double kappa);

    // The outer iterate u: the barrier's value, gradient and (per-cell PSD) Hessian there, in
    // step coordinates, as contained in the outer gradient and Hessian.
    void set_point(const Eigen::VectorXd &u);
    const Eigen::VectorXd &gradient() const { return gradient_; }
    // p^T H_barrier p.
    double curvature(const Eigen::VectorXd &p) const { return p.dot(hessian_ * p); }
    // The extra secant curvature applied to p (0 until a step was cut by the barrier).
    Eigen::VectorXd apply_secants(const Eigen::VectorXd &p) const;
    // The barrier's Hessian plus the secants, in step coordinates (the stiff part of the
    // outer model: the preconditioner is built from it).
    Eigen::SparseMatrix<double> stiffness() const;

    // The best fraction alpha in (0, alpha_max] of the step p and the model's change there:
    // alpha (slope + 1/2 alpha curvature) for the rest of R, plus the barrier's actual change.
    std::pair<double, double> best_fraction(const Eigen::VectorXd &p, double alpha_max, double slope,
                                            double curvature) const;

    // After a step p (reference step du = B p) that the barrier cut short: every cell it drove
    // deeper into the barrier gets the secant curvature over it. Returns whether any did.
    bool add_secants(const Eigen::VectorXd &p);

  private:
    double value_at(const Eigen::VectorXd &u) const;
    // secant_rows_ from secant_ at the current point.
    void build_secant_rows();

    const SimplexMesh<dim>            &mesh_;
    const Eigen::SparseMatrix<double> &basis_;
    double                             w_hat_, kappa_;
    Eigen::VectorXd                    u_;
    double                             value_ = 0;
    Eigen::VectorXd                    gradient_;
    Eigen::SparseMatrix<double>        hessian_;
    std::vector<double>                secant_;  // per cell, in units of kappa b''
    Eigen::SparseMatrix<double>        secant_rows_;  // row c: secant_c^(1/2) (d w_c / d u) B
  };
} // namespace ritr
