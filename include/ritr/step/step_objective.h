#pragma once
// The inner solve's objective as Newton sees it: the incremental potential E(z; u) of a term
// sum at its current reference mesh, over the state z = [body nodes, obstacle vertices]. It
// builds the collision candidates Newton's evaluations look at -- at the iterate for the
// derivatives, along the step for the line search -- and, in the first solve of a step,
// applies IPC's adaptive barrier stiffness between iterations.
#include <ritr/solver/newton.h>
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/terms/term_sum.h>

#include <limits>

namespace ritr
{
  template <int dim>
  class StepObjective : public NewtonObjective
  {
  public:
    explicit StepObjective(TermSum<dim> &terms)
      : terms_(terms)
      , hessian_(terms.mesh().cells)
      , barrier_(terms.template find<ContactBarrierTerm<dim>>())
    {}

    // IPC's adaptive stiffness: doubling (up to kappa_max) while the closest active distance
    // keeps shrinking; off until enabled, and after disable.
    void enable_adaptive_stiffness(double kappa_max, double bbox_diagonal);
    void disable_adaptive_stiffness() { adaptive_ = false; }

    void   begin_iteration(const Eigen::VectorXd &z) override;
    double value(const Eigen::VectorXd &z) override;
    void   gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g) override;
    void   hessian(const Eigen::VectorXd &z, Triplets &h, bool project) override;
    void   hessian_and_projection(const Eigen::VectorXd &z, Triplets &h, TripletChanges &projection) override;
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) override;

  private:
    void add_obstacle_diagonal(const Eigen::VectorXd &z, Triplets &h) const;

    TermSum<dim>            &terms_;
    MatrixAssembly<dim>      hessian_;   // storage reused across iterations
    ContactBarrierTerm<dim> *barrier_;   // null without contact
    // The pairs of the current Newton iteration: at its iterate for the derivatives, then
    // along its step for the line search's trials.
    CollisionCandidates candidates_;
    bool                adaptive_          = false;
    double              kappa_max_         = 0;
    double              bbox_diagonal_     = 1;
    double              previous_distance_ = std::numeric_limits<double>::infinity();
  };
} // namespace ritr
