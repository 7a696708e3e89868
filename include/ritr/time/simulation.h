#pragma once
// A simulation run: builds the mesh, materials, obstacles and boundary conditions from a
// Scene, validates the initial state, then steps in time (implicit Euler) or load
// (statics), writing the outputs of the output contract after every step.
#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/contact/contact_potential.h>
#include <ritr/elasticity/bulk_energy.h>
#include <ritr/output/run_directory.h>
#include <ritr/scene/expression.h>
#include <ritr/scene/scene.h>
#include <ritr/solver/newton.h>
#include <ritr/time/implicit_step.h>

#include <memory>
#include <optional>

namespace ritr
{
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

  template <int dim>
  class Simulation
  {
  public:
    // Builds everything and checks the initial state; throws InputError on bad input.
    explicit Simulation(const Scene &scene);
    ~Simulation();

    // Runs all steps and writes the outputs; throws ConvergenceError.
    void run();

    // Single step, for tests and drivers that inspect the state between steps.
    StepReport advance();

    const SimplexMesh<dim> &mesh() const { return mesh_; }
    const Eigen::VectorXd  &positions() const { return x_; }
    const Eigen::VectorXd  &velocities() const { return v_; }
    const Eigen::VectorXd  &reference() const { return u_; }
    double                  time() const { return time_; }
    const std::vector<StepReport> &history() const { return history_; }
    // Invariant checks that failed so far, one line each (also in summary.json).
    const std::vector<std::string> &invariant_violations() const { return invariant_violations_; }
    const BulkEnergy<dim>  &bulk_energy() const { return *bulk_; }
    const NewtonSolver     &newton_solver() const { return implicit_step_->newton(); }
    // Physical contact force on every body node (zero without contact).
    Eigen::VectorXd contact_forces() const;

  private:
    void setup_obstacles();
    void setup_dirichlet();
    void setup_adaptivity();
    void check_initial_state() const;
    double signed_cell_measure(unsigned int cell) const;  // at the reference positions
    Eigen::VectorXd state_targets(double t) const;  // kinematic entries at time t
    void            advance_adaptive(StepReport &report, const StepContext<dim> &context);
    // Fills the report's mesh invariants after a step and records any violation.
    void            check_invariants(StepReport &report);
    Eigen::VectorXd state() const;
    void write_step_output(unsigned int step);
    // A row of newton.csv (Solver/newton log); rows are numbered by step and by solve.
    void log_newton_iteration(const NewtonIterationRecord &record, const Eigen::VectorXd &z);
    // summary.json; `complete` only when every step is done, `failure` says why not.
    void write_summary(double total_seconds, bool complete, const std::string &failure = "") const;

    Scene                                      scene_;
    SimplexMesh<dim>                           mesh_;
    Eigen::VectorXd                            u_, x_, v_;
    std::unique_ptr<BulkEnergy<dim>>           bulk_;
    std::vector<contact::RigidObstacle<dim>>   obstacles_;
    std::unique_ptr<ContactPotential<dim>>     contact_;
    std::unique_ptr<ImplicitStep<dim>>         implicit_step_;
    std::unique_ptr<RitrSolver<dim>>           ritr_;  // with adaptivity on
    std::vector<bool>                          kinematic_;  // per state entry
    std::vector<std::pair<unsigned int, unsigned int>> dirichlet_nodes_;  // node, condition
    std::vector<Expression<dim>>               dirichlet_displacements_;
    std::optional<Expression<dim>>             load_factor_;
    Eigen::VectorXd                            obstacle_positions_;  // at the current time
    double                                     time_ = 0;
    unsigned int                               step_ = 0;
    std::vector<StepReport>                    history_;
    std::vector<std::string>                   invariant_violations_;
    std::unique_ptr<RunOutputs>                outputs_;
    unsigned int                               logged_step_ = 0, logged_solve_ = 0;
  };
} // namespace ritr
