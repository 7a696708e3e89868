#pragma once
// One time step of optimal r-adaptive in-timestep remeshing (paper Algorithm 1): an outer
// solve over the reference positions u of the objective R (the step's term sum with the
// reference measure barrier), with the physical admissibility x = argmin E(., u) solved by
// the implicit step at every trial mesh, and geometric admissibility kept by moving
// boundary nodes only within their (approximately) planar facet or straight edge, the
// measure barrier and a step filter that never lets a reference element invert.
//
// The default outer step is a trust-region Newton-CG on the exact reduced Hessian (`reduced`);
// the switches reproduce the paper's ablations: outer Hessian truncated | full | filtered
// (5.4, line search on R with the Newton driver), inertia corrected | uncorrected (4.3),
// projection in | after optimization (4.1), and admissibility geometric and/or physical
// (4.5; without physical admissibility x and u are minimised jointly).
#include <ritr/adaptivity/deformation_carrier.h>
#include <ritr/adaptivity/outer_model.h>
#include <ritr/adaptivity/outer_stop.h>
#include <ritr/adaptivity/quasi_newton_curvature.h>
#include <ritr/adaptivity/reduced_hessian.h>
#include <ritr/adaptivity/reference_penalties.h>
#include <ritr/adaptivity/ritr_options.h>
#include <ritr/solver/sparse_cholesky.h>
#include <ritr/step/implicit_step.h>
#include <ritr/terms/measure_barrier_term.h>
#include <ritr/terms/transferred_inertia_term.h>

#include <optional>
#include <tuple>

namespace ritr
{
  // Filled from the scene by ritr_settings() (time/stepper.h); the scene's AdaptivityScene is
  // the one home of their defaults.
  struct RitrSettings
  {
    RitrHessian  hessian                 = RitrHessian::reduced;
    bool         geometric_admissibility = true;
    bool         physical_admissibility  = true;
    double       epsilon_r               = 0;  // stop when |du|_inf <= epsilon_r (a length)
    // Trust region: stop when the predicted decrease is below this fraction of R's decrease
    // in the step so far (0: off).
    double       decrease_tolerance      = 0;
    // Inexact inner solves: a trial's Newton tolerance is loosened by min(this, |du|_inf /
    // epsilon_r) (at least 1); the step then ends with a tight solve at its mesh.
    double       inner_tolerance_factor  = 1;
    // Inexact inner solves: a trial's Newton stops after this many iterations (0: at its
    // tolerance); the step then ends with a tight solve at its mesh.
    unsigned int trial_iterations        = 0;
    unsigned int max_outer_iterations    = 0;
    // Trust region: each step's region starts with the radius the last step ended with
    // (quasi-newton always; reduced when set), instead of at the initial radius.
    bool         carry_trust_region      = false;
    // Trust region: the forcing term's cap, CG's largest residual on the outer model relative
    // to the outer gradient.
    double       model_tolerance         = 1e-2;
    double       sliding_tolerance       = 0;  // eps_b
    double       filter_threshold        = 1e-3;  // filtered Hessian: relative to the largest |dx/du|
    // Stiffness kappa_w of the reference measure barrier; 0 takes the contact barrier's
    // stiffness when there is contact, else (h^2) E / w_hat (see ritr_solver.cc).
    double       measure_barrier_stiffness = 0;
    // Of the velocity's transfer (the inertia term has its own, from the same scene entry).
    transfer::TransferIntegration transfer_integration = transfer::TransferIntegration::quadrature;
    // Dirichlet nodes that slide along their condition's boundary (trust-region solve only):
    // each prescribes the material point it carries, x = u + the uniform displacement.
    std::vector<std::pair<unsigned int, unsigned int>> sliding_dirichlet_nodes;  // node, condition
  };

  // A step's targets (set at the initial reference) with the entries of sliding Dirichlet
  // nodes moved to reference u: their displacement is uniform, so the target of the material
  // point a node carries is u plus the same displacement.
  Eigen::VectorXd sliding_dirichlet_targets(const Eigen::VectorXd &targets, const Eigen::VectorXd &u,
                                            const Eigen::VectorXd &initial_reference, const std::vector<int> &entries);

  template <int dim>
  class RitrSolver
  {
  public:
    // `inner` solves the implicit step on a given mesh over the terms of `inner.terms()`,
    // which must hold a MeasureBarrierTerm; `materials` give the mesh (connectivity, initial
    // reference: sliding anchors) and the stiffness scale; `quadrature` integrates the
    // velocity's L2 transfer.
    RitrSolver(const CellMaterials<dim> &materials, ImplicitStep<dim> &inner, const RitrSettings &settings,
               const SimplexQuadrature<dim> &quadrature);

    struct Result
    {
      Eigen::VectorXd u, z, v;
      double          objective = 0;
      // R at (argmin E(., u_t), u_t): the step never ends above it.
      double          initial_objective = 0;
      double          sliding_violation = 0;
      OuterStop       stop              = OuterStop::iteration_limit;
      unsigned int    outer_iterations = 0, inner_iterations = 0, line_search_trials = 0;
      double          inner_seconds = 0, transfer_seconds = 0, outer_solve_seconds = 0;
    };

    // Advances the step's start (u_t, z_t, v_t) by one step (dynamic: implicit Euler; static:
    // one load step, v ignored).
    Result step(const StepContext<dim> &step);

    // What the solver carries from one step to the next (the trust region's radius and the
    // quasi-Newton curvature), for checkpoints; restore throws std::invalid_argument for a
    // state of another mesh.
    Eigen::VectorXd carried_state() const;
    void            restore_carried_state(const Eigen::VectorXd &state);

  private:
    // The paper's outer Newton with a line search on R (truncated, full or filtered Hessian),
    // or without physical admissibility the joint one over (x, u): line_search_outer.h.
    void line_search_solve(const Eigen::VectorXd &targets, Result &r);
    // The exact reduced Hessian: Steihaug CG in a trust region whose radius follows the ratio
    // of R's actual to predicted change; trial states are predicted by the implicit-function
    // response of x before the inner solve polishes them.
    // A step whose accepted state was solved loosely goes on from a tight solve at its mesh.
    void trust_region_solve(const Eigen::VectorXd &targets, Result &r);
    void trust_region_iterations(const Eigen::VectorXd &targets, Result &r);
    // R at the trial mesh r.u + step.du, with the state r.z + dz (kept short of contact) solved;
    // returns (R or +infinity if the inner solve failed, u, z).
    std::tuple<double, Eigen::VectorXd, Eigen::VectorXd> trial(const typename OuterModel<dim>::Step &step,
                                                               Eigen::VectorXd dz, const Eigen::VectorXd &targets,
                                                               Result &r);
    // The state's change at the trial mesh of `step` from (z, u): the implicit-function response
    // with the reduced Hessian, else the deformation carried over (deformation_carrier.h).
    Eigen::VectorXd predicted_state_change(const typename OuterModel<dim>::Step &step,
                                           const std::optional<ReducedHessian> &hessian, const Eigen::VectorXd &z,
                                           const Eigen::VectorXd &u) const;
    // B^T dR/du at the solved state z on mesh u: the reduced gradient, no solve needed
    // (dE/dx = 0 there), with sliding Dirichlet nodes' prescribed positions following u;
    // optionally without the measure barrier's part (the quasi-Newton curvature's gradient).
    Eigen::VectorXd reduced_gradient(const Eigen::VectorXd &z, const Eigen::VectorXd &u,
                                     bool without_measure_barrier = false);
    // Quasi-Newton: the curvature pair from the last tightly solved state of the step to the
    // one at mesh u with the given gradient (without the measure barrier), which starts the next.
    void curvature_pair_to(const Eigen::VectorXd &u, const Eigen::VectorXd &rest_gradient);
    // x = argmin E(., u) warm-started from z (`near_solution`: predicted to first order), with
    // the tolerance loosened by `tolerance_scale` and Newton stopped after `iteration_cap`
    // iterations (0: none); whether it converged, nothing if the inner solve failed.
    std::optional<bool> solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z, const Eigen::VectorXd &targets,
                                      Result &r, bool near_solution = false, double tolerance_scale = 1.0,
                                      unsigned int iteration_cap = 0);
    // R at (z, u).
    double objective(const Eigen::VectorXd &z, const Eigen::VectorXd &u);
    // Largest step fraction in (0, 1] keeping every reference cell above a fifth of its measure.
    double step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du) const;
    // The same for the step ddu taken after du from u (cells measured against u).
    double step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du, const Eigen::VectorXd &ddu) const;
    double transfer_seconds() const;
    // The step's targets (at the initial reference) with the sliding Dirichlet nodes' moved
    // to reference u.
    Eigen::VectorXd targets_at(const Eigen::VectorXd &targets, const Eigen::VectorXd &u) const;

    const SimplexMesh<dim>              &mesh_;
    TermSum<dim>                        &terms_;
    ImplicitStep<dim>                   &inner_;
    RitrSettings                         settings_;
    MeasureBarrierTerm<dim>             &measure_barrier_;
    const TransferredInertiaTerm<dim>   *inertia_;  // null: the predictor is not transferred
    // pi_t(x_t, u) for the velocity update, whichever form the inertia has.
    transfer::TransferOperator<dim>      velocity_transfer_;
    double                               velocity_transfer_seconds_ = 0;
    std::vector<SlidingConstraint<dim>>  sliding_;
    DeformationCarrier<dim>              carrier_;
    // The quasi-Newton outer curvature, kept across steps, and the mesh of the step's last
    // tightly solved state (empty: none yet) with its gradient without the measure barrier.
    QuasiNewtonCurvature                 quasi_newton_;
    Eigen::VectorXd                      pair_start_, pair_gradient_;
    double                               carried_radius_ = 0;  // the region's radius at the last step's end
    // u moves in the span of basis_ (n_u x m): every direction for interior nodes, the
    // tangents of the sliding facet or edge for boundary nodes, none for corners and
    // Dirichlet nodes. Sliding thus holds exactly, not through a penalty.
    Eigen::SparseMatrix<double>          basis_;
    std::vector<int>                     free_state_;  // non-kinematic state entries
    // Prescribed entries of sliding Dirichlet nodes: x_p = u_p + displacement follows u.
    std::vector<int>                     following_prescribed_;
    // Inexact inner solves: whether the last trial and the accepted state were solved loosely,
    // and whether the step has gone over to tight solves.
    bool last_trial_loose_ = false, state_loose_ = false, tight_only_ = false;
    double                               w_hat_ = 0;
    double                               youngs_modulus_ = 0;
    NewtonSolver                         outer_newton_;    // the line-search outer solves
    SparseCholesky                       state_cholesky_;  // H_xx of the reduced Hessian
  };
} // namespace ritr
