#pragma once
// Lagged IPC friction D(z, u) = sum_j w_j(u) lambda_j f0(|u_j|) mu (contact/friction.h): the
// normal forces and tangents are lagged from a state of the step, the slip is measured from
// the start-of-step state, and each normal force scales with its constraint's reference
// boundary measure, so that D depends on u like the barrier. Empty in 1D and without
// friction.
#include <ritr/contact/friction.h>
#include <ritr/terms/energy_term.h>

namespace ritr
{
  template <int dim>
  class FrictionTerm : public EnergyTerm<dim>
  {
  public:
    FrictionTerm(const CollisionMesh<dim> &collisions, double coefficient, double epsilon_v_times_h)
      : collisions_(collisions)
      , coefficient_(coefficient)
      , epsilon_v_times_h_(epsilon_v_times_h)
    {}

    // Lags the friction: normal forces (with the barrier stiffness kappa, at the current
    // reference weights) and tangents from z_lagged, slip measured from z_start.
    void lag(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates, const Eigen::VectorXd &z_start,
             double kappa);

    bool   is_contact() const override { return true; }
    // The lagged normal forces follow their weights to the new mesh.
    void   set_reference(const Eigen::VectorXd &u) override;
    const char *name() const override { return "friction"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    void   add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const override;
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    const CollisionMesh<dim>                     &collisions_;
    double                                        coefficient_, epsilon_v_times_h_;
    std::vector<contact::FrictionConstraint<dim>> friction_;
    Eigen::MatrixXd                               start_;  // collision vertices at the start of the step
    // Per friction constraint: the weight's sources and the normal force per unit weight.
    std::vector<typename CollisionMesh<dim>::WeightSources> sources_;
    std::vector<double>                                     unit_force_;
  };
} // namespace ritr
