#pragma once
// One time (or load) step, on a fixed mesh or with r-adaptive in-timestep remeshing: both
// read the step's context and return where the step ended, so that the time loop does not
// care which one runs. make_stepper() picks and configures one from the problem's scene.
#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/problem/problem.h>
#include <ritr/solver/newton.h>
#include <ritr/step/implicit_step.h>
#include <ritr/step/step_context.h>

#include <limits>
#include <memory>

namespace ritr
{
  // Sees every Newton iteration of an implicit step (newton.csv).
  using NewtonMonitor = decltype(NewtonSettings::monitor);

  // What one step did, for log.csv and the progress line.
  struct StepReport
  {
    unsigned int step = 0;
    double       time = 0;
    double       energy = 0;
    unsigned int newton_iterations = 0;
    unsigned int outer_iterations  = 0;
    unsigned int line_search_trials = 0;
    // r-adaptivity: R at the step's start mesh (the step never ends above it), the boundary
    // sliding violation and the time split between inner solves, transfer and outer solves.
    double       initial_objective = 0;
    double       sliding_violation = 0;
    double       inner_seconds = 0, transfer_seconds = 0, outer_solve_seconds = 0;
    double       min_distance = std::numeric_limits<double>::infinity();
    double       min_reference_measure = 0;
    double       min_deformed_jacobian = 0;
    double       wall_seconds = 0;
  };

  // Where a step ended, and how it got there.
  struct StepResult
  {
    Eigen::VectorXd u;  // reference positions
    Eigen::VectorXd z;  // state: [body node positions, obstacle vertices]
    Eigen::VectorXd v;  // body node velocities
    StepReport      report;  // the solver's part; the mesh invariants are filled in later
    // r-adaptivity: why the outer iteration stopped (a fixed-mesh step has none).
    std::optional<OuterStop> outer_stop;
  };

  template <int dim>
  class Stepper
  {
  public:
    virtual ~Stepper() = default;
    // Throws ConvergenceError when the step cannot be solved.
    virtual StepResult step(const StepContext<dim> &context) = 0;
    // The Newton solver of the implicit step (linear-solve statistics for the summary).
    const NewtonSolver &newton_solver() const { return implicit_step_->newton(); }

  protected:
    std::unique_ptr<ImplicitStep<dim>> implicit_step_;
  };

  // The stepper the scene asks for, on the problem's terms (which it shares and must not
  // outlive). `monitor` (may be empty) sees every Newton iteration of the implicit step.
  // Throws InputError for adaptivity settings the problem cannot use.
  template <int dim>
  std::unique_ptr<Stepper<dim>> make_stepper(Problem<dim> &problem, const NewtonMonitor &monitor);
} // namespace ritr
