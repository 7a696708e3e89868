#pragma once
// One implicit step on a given reference mesh u: minimise the incremental potential of the
// step's terms over the state z = [body nodes, obstacle vertices] with Newton, kinematic
// entries (Dirichlet nodes, scripted obstacles) driven to their targets, IPC's barrier
// stiffness and lagged friction. The fixed-mesh simulation calls it once per step;
// r-adaptivity calls it for every candidate reference mesh (the physical admissibility
// x = argmin E(., u)).
#include <ritr/elasticity/cell_materials.h>
#include <ritr/solver/newton.h>
#include <ritr/step/step_objective.h>

#include <stdexcept>

namespace ritr
{
  // A step that could not be solved; the run stops with exit code 3.
  class ConvergenceError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Filled from the scene by implicit_step_settings() (time/stepper.h).
  struct ImplicitStepSettings
  {
    NewtonSettings newton;
    unsigned int   friction_iterations = 1;
    double         barrier_stiffness   = 0;  // fixed kappa; 0 selects IPC's adaptive rule
  };

  template <int dim>
  class ImplicitStep
  {
  public:
    // `terms` and `materials` (IPC's stiffness rule takes the mean nodal mass) are shared
    // and must outlive the step.
    ImplicitStep(TermSum<dim> &terms, const CellMaterials<dim> &materials, const std::vector<bool> &kinematic,
                 const ImplicitStepSettings &settings);

    struct Report
    {
      unsigned int iterations = 0, line_search_trials = 0;
      double       energy = 0;
      bool         converged = true;  // false: stopped at an iteration cap (solve_on_mesh)
    };

    // First solve of a step, on its start-of-step mesh: the terms take the step's context,
    // the barrier stiffness is initialised at z (IPC's rule, adapted while Newton runs) and
    // friction is lagged `friction_iterations` times, with slip measured from the
    // start-of-step state. Throws ConvergenceError.
    Report solve_start_of_step(const StepContext<dim> &step, Eigen::VectorXd &z);
    // Later solves of the same step on another reference u (r-adaptivity's trial meshes),
    // warm-started from z: the stiffness and lagged friction stay frozen, so that the
    // objective is one function across trials. `near_solution`: z is predicted to first
    // order (r-ITR trial meshes), so an adaptive Hessian projection starts exact.
    // `tolerance_scale` loosens the Newton tolerance and `iteration_cap` (0: none) stops Newton
    // early without an error (inexact inner solves of the outer one: E at any admissible state
    // bounds its minimum from above). Throws ConvergenceError if Newton fails otherwise.
    Report solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z, const Eigen::VectorXd &targets,
                         bool near_solution = false, double tolerance_scale = 1.0, unsigned int iteration_cap = 0);

    const std::vector<bool> &kinematic() const { return kinematic_; }
    const NewtonSolver      &newton() const { return newton_; }
    TermSum<dim>            &terms() { return terms_; }

  private:
    // Whether every prescribed entry of z is at its target.
    bool prescribed_reached(const Eigen::VectorXd &z, const Eigen::VectorXd &targets) const;

    TermSum<dim>             &terms_;
    const CellMaterials<dim> &materials_;
    std::vector<bool>         kinematic_;
    ImplicitStepSettings      settings_;
    StepObjective<dim>        objective_;
    NewtonSolver              newton_;
  };
} // namespace ritr
