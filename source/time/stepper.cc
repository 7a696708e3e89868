#include <ritr/common/input_error.h>
#include <ritr/metrics/mesh_metrics.h>
#include <ritr/time/stepper.h>

#include <cmath>

namespace ritr
{
  namespace
  {
    // The implicit step on the start-of-step mesh, the mesh kept.
    template <int dim>
    class FixedMeshStepper : public Stepper<dim>
    {
    public:
      explicit FixedMeshStepper(std::unique_ptr<ImplicitStep<dim>> implicit_step)
      {
        this->implicit_step_ = std::move(implicit_step);
      }

      StepResult step(const StepContext<dim> &context) override
      {
        StepResult result;
        result.u = context.u_start;
        result.z = context.z_start;
        try
          {
            const auto r = this->implicit_step_->solve_start_of_step(context, result.z);
            result.report.newton_iterations  = r.iterations;
            result.report.line_search_trials = r.line_search_trials;
            result.report.energy             = r.energy;
          }
        catch (const ConvergenceError &e)
          {
            throw ConvergenceError("step " + std::to_string(context.step) + " (t = " + std::to_string(context.time) +
                                   ") did not converge: " + e.what());
          }
        const Eigen::VectorXd x = result.z.head(context.u_start.size());
        result.v = context.dynamic ? Eigen::VectorXd((x - context.x_start()) / context.time_step) :
                                     Eigen::VectorXd::Zero(x.size());
        return result;
      }
    };

    // Optimal r-adaptive in-timestep remeshing: the mesh moves within the step.
    template <int dim>
    class RitrStepper : public Stepper<dim>
    {
    public:
      RitrStepper(std::unique_ptr<ImplicitStep<dim>> implicit_step, std::unique_ptr<RitrSolver<dim>> solver)
        : solver_(std::move(solver))
      {
        this->implicit_step_ = std::move(implicit_step);
      }

      Eigen::VectorXd carried_state() const override { return solver_->carried_state(); }
      void restore_carried_state(const Eigen::VectorXd &state) override { solver_->restore_carried_state(state); }

      StepResult step(const StepContext<dim> &context) override
      {
        typename RitrSolver<dim>::Result r;
        try
          {
            r = solver_->step(context);
          }
        catch (const ConvergenceError &e)
          {
            throw ConvergenceError("step " + std::to_string(context.step) + ": " + e.what());
          }
        StepResult result;
        result.u                          = r.u;
        result.z                          = r.z;
        result.v                          = r.v;
        result.report.outer_stop          = r.stop;
        result.report.energy              = r.objective;
        result.report.initial_objective   = r.initial_objective;
        result.report.sliding_violation   = r.sliding_violation;
        result.report.newton_iterations   = r.inner_iterations;
        result.report.outer_iterations    = r.outer_iterations;
        result.report.line_search_trials  = r.line_search_trials;
        result.report.inner_seconds       = r.inner_seconds;
        result.report.transfer_seconds    = r.transfer_seconds;
        result.report.outer_solve_seconds = r.outer_solve_seconds;
        return result;
      }

    private:
      // Owned here, but built on the implicit step above: destroyed first.
      std::unique_ptr<RitrSolver<dim>> solver_;
    };

  } // namespace

  template <int dim>
  RitrSettings ritr_settings(const Problem<dim> &problem)
  {
    const AdaptivityScene &a = problem.scene.adaptivity;
    RitrSettings           settings;
    const bool dynamic               = problem.scene.dynamic();
    settings.hessian                 = a.hessian != RitrHessian::automatic ? a.hessian :
                                       dynamic                             ? RitrHessian::quasi_newton :
                                                                             RitrHessian::reduced;
    settings.geometric_admissibility = a.admissibility == Admissibility::geometric || a.admissibility == Admissibility::both;
    settings.physical_admissibility  = a.admissibility == Admissibility::physical || a.admissibility == Admissibility::both;
    settings.sliding_tolerance         = a.sliding_tolerance;
    settings.max_outer_iterations      = a.max_iterations > 0 ? a.max_iterations : dynamic ? 1 : 100;
    settings.decrease_tolerance = a.decrease_tolerance > 0 ? a.decrease_tolerance : std::sqrt(a.epsilon_r);
    settings.inner_tolerance_factor = a.inner_tolerance_factor;
    settings.trial_iterations       = a.trial_iterations;
    settings.carry_trust_region     = a.carry_trust_region;
    settings.model_tolerance        = a.model_tolerance;
    settings.measure_barrier_stiffness = a.measure_barrier_stiffness;
    settings.transfer_integration      = problem.transfer_integration();
    settings.sliding_dirichlet_nodes   = problem.sliding_dirichlet_nodes;
    // epsilon_r is given relative to the bounding-box diagonal of the reference domain.
    settings.epsilon_r = a.epsilon_r * bounding_box_diagonal<dim>(problem.initial_reference);
    return settings;
  }

  template <int dim>
  ImplicitStepSettings implicit_step_settings(const Problem<dim> &problem, const NewtonMonitor &monitor)
  {
    const Scene         &scene = problem.scene;
    ImplicitStepSettings settings;
    settings.newton.max_iterations = scene.solver.max_iterations;
    settings.newton.projection     = scene.solver.hessian_projection;
    // Both tolerances are relative to the bodies' size, so that a scene means the same in any
    // unit; obstacles (a ground plane may be any size) do not count.
    const double length       = bounding_box_diagonal<dim>(problem.initial_reference);
    settings.newton.tolerance = scene.dynamic() ? scene.solver.newton_tolerance * scene.time_step * length :
                                                  scene.solver.static_tolerance * length;
    settings.newton.monitor     = monitor;
    if (problem.work_share.distributed())
      {
        // Trilinos solves the projected Newton system; with the direct solver its inverse
        // preconditions the trust region's CG as CHOLMOD's does. One V-cycle of the multigrid
        // is too loose a preconditioner for it (a 3D ball on spikes: 55 Newton iterations
        // against 31, ending 1.8e-3 away), so with amg the trust region becomes projected
        // Newton. The shifted exact Hessian needs CHOLMOD's factor of the whole matrix.
        const HessianProjection p = scene.solver.hessian_projection;
        if (p == HessianProjection::never || p == HessianProjection::adaptive)
          throw InputError(scene.where("Solver/hessian projection") + ": '" +
                           std::string(name_of(hessian_projection_names, p)) +
                           "' runs on one process only; on several, use trust-region or always");
        if (scene.solver.distributed_solver == DistributedSolver::amg)
          settings.newton.projection = HessianProjection::always;
        settings.newton.work_share         = &problem.work_share;
        settings.newton.distributed_solver = scene.solver.distributed_solver;
      }
    settings.friction_iterations = scene.contact.friction_iterations;
    settings.barrier_stiffness   = scene.contact.barrier_stiffness;
    return settings;
  }

  template <int dim>
  std::unique_ptr<Stepper<dim>> make_stepper(Problem<dim> &problem, const NewtonMonitor &monitor)
  {
    const Scene &scene         = problem.scene;
    auto         implicit_step = std::make_unique<ImplicitStep<dim>>(*problem.terms, *problem.materials, problem.kinematic,
                                                                     implicit_step_settings(problem, monitor));
    if (!scene.adaptivity.enabled)
      return std::make_unique<FixedMeshStepper<dim>>(std::move(implicit_step));

    const RitrSettings settings = ritr_settings(problem);
    if (!settings.physical_admissibility && problem.collisions)
      throw InputError(scene.where("Adaptivity/admissibility") +
                       ": without physical admissibility contact is not supported");
    if (!settings.sliding_dirichlet_nodes.empty() &&
        (!is_trust_region(settings.hessian) || !settings.physical_admissibility ||
         !settings.geometric_admissibility))
      throw InputError(problem.sliding_dirichlet_entry +
                       ": needs Adaptivity/hessian = reduced or quasi-newton and admissibility = both (nodes slide along facets)");
    auto solver = std::make_unique<RitrSolver<dim>>(*problem.materials, *implicit_step, settings,
                                                    problem.transfer_quadrature());
    return std::make_unique<RitrStepper<dim>>(std::move(implicit_step), std::move(solver));
  }

#define RITR_INSTANTIATE(dim)                                                                                          \
  template std::unique_ptr<Stepper<dim>> make_stepper<dim>(Problem<dim> &, const NewtonMonitor &);                     \
  template ImplicitStepSettings          implicit_step_settings<dim>(const Problem<dim> &, const NewtonMonitor &);     \
  template RitrSettings                  ritr_settings<dim>(const Problem<dim> &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
