#pragma once
// Lagged IPC friction D(z, u) = sum_j w_j(u) lambda_j f0(|s_j|) mu (contact/friction.h): the
// normal forces and tangents are lagged from a state of the step and each normal force
// scales with its constraint's reference boundary measure, so that D depends on u like the
// barrier.
//
// The slip s_j is that of material points: a body vertex whose reference position moved
// from u_i^t to u_i carries the material point that was at phi_t(u_i) at the start of the
// step (phi_t the start-of-step deformation, piecewise linear on the start-of-step mesh),
// so its slip is x_i - phi_t(u_i), not x_i - x_i^t. Measured from the node's own start
// position instead, a mesh whose contact nodes stay put in space while the material flows
// past them would show no slip and pay no friction. Empty in 1D and without friction.
#include <ritr/contact/friction.h>
#include <ritr/terms/energy_term.h>
#include <ritr/transfer/old_mesh_locator.h>

namespace ritr
{
  template <int dim>
  class FrictionTerm : public EnergyTerm<dim>
  {
  public:
    FrictionTerm(const CollisionMesh<dim> &collisions, double coefficient, double epsilon_v_times_h);

    // The start-of-step mesh and state the slip is measured from.
    void begin_step(const StepContext<dim> &context) override;
    // Lags the friction: normal forces (with the barrier stiffness kappa, at the current
    // reference weights) and tangents from z_lagged.
    void lag(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates, double kappa);

    bool   is_contact() const override { return true; }
    // The lagged normal forces follow their weights to the new mesh, the slip's start
    // positions follow the material points.
    void   set_reference(const Eigen::VectorXd &u) override;
    const char *name() const override { return "friction"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    void   add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const override;
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    using Jacobian = Eigen::Matrix<double, dim, dim>;
    // The slip origins of the stencils' body vertices at reference u and their derivatives.
    void     update_start(const Eigen::VectorXd &u);
    // d phi_t / dX in old cell o: the cell's start-of-step deformation gradient.
    Jacobian start_gradient(unsigned int o) const;

    const CollisionMesh<dim>                     &collisions_;
    double                                        coefficient_, epsilon_v_times_h_;
    std::vector<contact::FrictionConstraint<dim>> friction_;
    Eigen::VectorXd                               u_start_, z_start_;
    // Built in a step's first evaluation on a moved mesh (a fixed mesh never needs it).
    transfer::OldMeshLocator<dim>                 old_mesh_;
    bool                                          old_mesh_built_ = false;
    // Per node: the cells that own a boundary facet through it (an unmoved node sits on a kink
    // of phi_t; these cells' gradients, averaged, are the slopes along the boundary it slides on).
    std::vector<std::vector<unsigned int>>        boundary_cells_;
    Eigen::MatrixXd                               start_;  // collision vertices' slip origins
    // Collision vertices of the body in some stencil, and d origin / d u of each.
    std::vector<int>                              stencil_vertices_;
    std::vector<Jacobian>                         origin_gradients_;
    // Per friction constraint: the weight's sources and the normal force per unit weight.
    std::vector<typename CollisionMesh<dim>::WeightSources> sources_;
    std::vector<double>                                     unit_force_;
  };
} // namespace ritr
