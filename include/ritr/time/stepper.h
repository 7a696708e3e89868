#pragma once
// One time (or load) step, on a fixed mesh or with r-adaptive in-timestep remeshing: both
// read the step's context and return where the step ended, so that the time loop does not
// care which one runs. make_stepper() picks and configures one from the problem's scene.
#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/problem/problem.h>
#include <ritr/solver/newton.h>
#include <ritr/step/implicit_step.h>
#include <ritr/time/step_report.h>

#include <memory>
#include <stdexcept>

namespace ritr
{
  // Sees every Newton iteration of an implicit step (newton.csv).
  using NewtonMonitor = decltype(NewtonSettings::monitor);

  // Where a step ended, and how it got there.
  struct StepResult
  {
    Eigen::VectorXd u;  // reference positions
    Eigen::VectorXd z;  // state: [body node positions, obstacle vertices]
    Eigen::VectorXd v;  // body node velocities
    StepReport      report;  // the solver's part; the mesh invariants are filled in later
  };

  template <int dim>
  class Stepper
  {
  public:
    virtual ~Stepper() = default;
    // Throws ConvergenceError when the step cannot be solved.
    virtual StepResult step(const StepContext<dim> &context) = 0;
    // What the stepper carries from one step to the next besides the state (the checkpoint
    // keeps it, so that a resumed run repeats the uninterrupted one): nothing on a fixed mesh.
    virtual Eigen::VectorXd carried_state() const { return {}; }
    // Takes back what carried_state() gave; throws std::invalid_argument if it cannot be this
    // stepper's.
    virtual void restore_carried_state(const Eigen::VectorXd &state)
    {
      if (state.size() != 0)
        throw std::invalid_argument("a fixed-mesh step carries no state");
    }
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

  // The settings make_stepper() gives the implicit step and the r-ITR solver (tests build
  // either from them).
  template <int dim>
  ImplicitStepSettings implicit_step_settings(const Problem<dim> &problem, const NewtonMonitor &monitor);
  template <int dim>
  RitrSettings ritr_settings(const Problem<dim> &problem);
} // namespace ritr
