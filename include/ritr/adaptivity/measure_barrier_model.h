#pragma once
// The reference measure barrier (eq. 21) inside the outer trust-region model. The barrier is
// C2 at its threshold w_hat and then grows like kappa (w_hat - w)^3 / w_hat with the contact
// stiffness kappa: a quadratic model taken at a cell outside (or just inside) the threshold
// has no curvature there and proposes steps that drive the cell deep into it. The barrier
// depends on u alone and costs one pass over the cells, so the model keeps it exact: the
// outer model is quadratic in the rest of R and takes the barrier's actual value, gradient
// and Hessian wherever the step has led (outer_model.h). The barrier's Hessian is 0 at the
// threshold, so a cell just outside or inside it is invisible to CG: a cell that a step
// drove into the barrier gets the secant curvature of the barrier over that step,
// kappa_c grad w grad w^T, in CG's Hessian for the rest of the time step, so that the next
// directions slide along the barrier instead of into it.
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

    // The barrier at u + B p, in step coordinates; the Hessian is projected per cell to be
    // positive semi-definite, as the outer Hessians take it.
    struct Derivatives
    {
      double                      value = 0;
      Eigen::VectorXd             gradient;
      Eigen::SparseMatrix<double> hessian;
    };

    // The outer iterate u, whose barrier derivatives the outer gradient and Hessian contain.
    void set_point(const Eigen::VectorXd &u);
    const Derivatives &at_point() const { return base_; }
    // The barrier after the step p from the outer iterate.
    Derivatives at(const Eigen::VectorXd &p) const;

    // The best fraction alpha in (0, alpha_max] of the step d taken from p, and the model's
    // change there: alpha (slope + 1/2 alpha curvature) for the rest of R, plus the barrier's
    // actual change from p (whose barrier value is `value_at_p`).
    std::pair<double, double> best_fraction(const Eigen::VectorXd &p, const Eigen::VectorXd &d, double value_at_p,
                                            double alpha_max, double slope, double curvature) const;

    // The extra secant curvature (0 until a step was cut by the barrier), as a matrix in step
    // coordinates.
    Eigen::SparseMatrix<double> secants() const;
    // After the step from p to p + d, which the barrier cut short: every cell it drove deeper
    // into the barrier gets the secant curvature over it. Returns whether any did.
    bool add_secants(const Eigen::VectorXd &p, const Eigen::VectorXd &d);

  private:
    double value_at(const Eigen::VectorXd &u) const;
    // secant_rows_ from secant_ at the current point.
    void build_secant_rows();

    const SimplexMesh<dim>            &mesh_;
    const Eigen::SparseMatrix<double> &basis_;
    double                             w_hat_, kappa_;
    Eigen::VectorXd                    u_;
    Derivatives                        base_;
    std::vector<double>                secant_;       // per cell, in units of kappa b''
    Eigen::SparseMatrix<double>        secant_rows_;  // row c: secant_c^(1/2) (d w_c / d u) B
  };
} // namespace ritr
