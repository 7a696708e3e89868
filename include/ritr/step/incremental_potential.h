#pragma once
// The objective of one implicit step over the state z = [body nodes, obstacle vertices]:
// the cell terms (inertia, elasticity, gravity) plus IPC barrier and lagged friction, with
// IPC's adaptive barrier stiffness updated between Newton iterations.
#include <ritr/contact/contact_potential.h>
#include <ritr/elasticity/bulk_energy.h>
#include <ritr/solver/newton.h>

namespace ritr
{
  template <int dim>
  class IncrementalPotential : public NewtonObjective
  {
  public:
    IncrementalPotential(BulkEnergy<dim> &bulk, ContactPotential<dim> *contact,
                         const Eigen::VectorXd &reference)
      : bulk_(bulk), contact_(contact), reference_(reference)
    {}

    // Adaptive stiffness: doubling when the closest active distance keeps shrinking.
    void enable_adaptive_stiffness(double kappa_max, double bbox_diagonal)
    {
      adaptive_      = true;
      kappa_max_     = kappa_max;
      bbox_diagonal_ = bbox_diagonal;
      previous_distance_ = std::numeric_limits<double>::infinity();
    }
    void disable_adaptive_stiffness() { adaptive_ = false; }

    // A term l^T x added to the objective (r-adaptivity: the transferred inertia target
    // -rho A_t(u) x_pred, which is linear in x for a fixed candidate mesh u).
    void set_linear_term(const Eigen::VectorXd &l) { linear_term_ = l; }

    void begin_iteration(const Eigen::VectorXd &z) override;
    double value(const Eigen::VectorXd &z) override;
    void   gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g) override;
    void   hessian(const Eigen::VectorXd &z, Triplets &h, bool project) override;
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) override;

    // Gradient of the cell terms alone (IPC's stiffness initialisation compares it with
    // the barrier gradient).
    Eigen::VectorXd bulk_gradient(const Eigen::VectorXd &z) const;

  private:
    Eigen::VectorXd body_positions(const Eigen::VectorXd &z) const { return z.head(reference_.size()); }

    BulkEnergy<dim>       &bulk_;
    ContactPotential<dim> *contact_;
    // The pairs of the current Newton iteration: at its iterate for the derivatives, then
    // along its step for the line search's trials.
    CollisionCandidates    candidates_;
    const Eigen::VectorXd &reference_;
    Eigen::VectorXd        linear_term_;
    bool                   adaptive_          = false;
    double                 kappa_max_         = 0;
    double                 bbox_diagonal_     = 1;
    double                 previous_distance_ = std::numeric_limits<double>::infinity();
  };
} // namespace ritr
