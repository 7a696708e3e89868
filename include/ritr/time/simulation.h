#pragma once
// A simulation run: the time (or load) loop. The problem comes from make_problem(), each
// step from a Stepper (fixed mesh or r-adaptive), the checks after it from the
// InvariantChecker; the outputs of the output contract are written after every step, and
// with every VTU frame a checkpoint that resume() continues from.
#include <ritr/output/directory_lock.h>
#include <ritr/output/run_directory.h>
#include <ritr/problem/problem.h>
#include <ritr/time/invariants.h>
#include <ritr/time/stepper.h>

#include <chrono>
#include <cstdint>
#include <memory>

namespace ritr
{
  template <int dim>
  class Simulation
  {
  public:
    // Builds everything and checks the initial state; throws InputError on bad input. On
    // several processes (`share`), every process runs the simulation together and the
    // writer alone (rank 0) writes the outputs, which are then those of a serial run.
    explicit Simulation(const Scene &scene, const WorkShare &share = WorkShare());
    ~Simulation();

    // Takes the scene's output directory for this process (creating it for a new run): no
    // other run can write there until this simulation ends. run() and resume() take it
    // themselves; taken earlier, a refusal comes before anything is printed. Throws
    // InputError naming the directory, and the process that holds it.
    void claim_output_directory(bool resuming);

    // Runs all steps and writes the outputs; throws ConvergenceError.
    void run();

    // Continues the run in the scene's output directory from its checkpoint.bin, writing the
    // outputs as run() does, as if it had never stopped. Returns false, touching nothing,
    // when that run is already complete. Throws InputError, touching nothing, when there is
    // no checkpoint or it is damaged or of another scene; ConvergenceError as run().
    bool resume();

    // Single step, for tests and drivers that inspect the state between steps.
    StepReport advance();

    // The scene as the problem settled it (with the start time of a `start from` frame).
    const Scene            &scene() const { return scene_; }
    const SimplexMesh<dim> &mesh() const { return mesh_; }
    const Eigen::VectorXd  &positions() const { return x_; }
    const Eigen::VectorXd  &velocities() const { return v_; }
    const Eigen::VectorXd  &reference() const { return u_; }
    double                  time() const { return time_; }
    const std::vector<StepReport> &history() const { return history_; }
    // Invariant checks that failed so far, one line each (also in summary.json).
    const std::vector<std::string> &invariant_violations() const { return invariant_violations_; }
    const CellMaterials<dim> &materials() const { return *problem_->materials; }
    const TermSum<dim>       &terms() const { return terms_; }
    const NewtonSolver     &newton_solver() const { return stepper_->newton_solver(); }
    // Physical contact force on every body node (zero without contact).
    Eigen::VectorXd contact_forces() const;

  private:
    Eigen::VectorXd state() const;  // z = [x, obstacle vertices]
    // The steps that write VTU frames and a checkpoint: the first and last, every `output every`.
    bool writes_frame(unsigned int step) const;
    // claim_output_directory()'s work, by the process that writes.
    void claim_directory(bool resuming);
    void write_step_output(unsigned int step);
    // The time loop from step_ to the end, with its outputs; throws ConvergenceError.
    void run_steps();
    // RunOutputs for the scene's directory, its CSV files holding their headers (the writer's
    // only: the other processes of a shared run have none, and write nothing).
    void create_outputs();
    bool is_writer() const { return problem_->work_share.is_writer(); }
    void append_log_row(const StepReport &r);
    void flush_logs() const;
    // resume(): the writer's files as they were at the checkpoint (collections and logs).
    void rewrite_outputs_up_to_checkpoint(const std::string &newton_rows);
    // checkpoint.bin for the state after step_ (simulation_resume.cc).
    void write_checkpoint() const;
    // The per-frame files of the frames up to `last_step`, as named in the output directory.
    std::vector<std::string> frame_files(unsigned int last_step) const;
    // Identifies the scene a checkpoint belongs to: its parameters (`listing`, a
    // Scene::parameter_listing) and its initial mesh.
    std::uint64_t scene_fingerprint(const std::string &listing) const;
    // Wall time of the run so far, over every process that ran a part of it.
    double wall_seconds() const;
    // A row of newton.csv (Solver/newton log); rows are numbered by step and by solve.
    void log_newton_iteration(const NewtonIterationRecord &record, const Eigen::VectorXd &z);
    // summary.json; `complete` only when every step is done, `failure` says why not.
    void write_summary(double total_seconds, bool complete, const std::string &failure = "") const;

    std::unique_ptr<Problem<dim>>              problem_;
    // Parts of the problem the time loop and the outputs read.
    const Scene                               &scene_;
    const SimplexMesh<dim>                    &mesh_;
    const std::vector<contact::RigidObstacle<dim>> &obstacles_;
    TermSum<dim>                              &terms_;
    std::unique_ptr<Stepper<dim>>              stepper_;
    InvariantChecker<dim>                      invariants_;
    Eigen::VectorXd                            u_, x_, v_;
    Eigen::VectorXd                            obstacle_positions_;  // at the current time
    double                                     barrier_stiffness_ = 0;  // the last step's (StepContext)
    double                                     time_ = 0;
    unsigned int                               step_ = 0;
    std::vector<StepReport>                    history_;
    std::vector<std::string>                   invariant_violations_;
    std::vector<std::pair<std::string, double>> last_step_terms_;  // summary.json's final_energy_terms, at the end
    std::unique_ptr<OutputDirectoryLock>       directory_lock_;  // claim_output_directory(), the writer's
    bool                                       claimed_ = false;  // by every process
    std::unique_ptr<RunOutputs>                outputs_;
    unsigned int                               logged_step_ = 0, logged_solve_ = 0;
    std::uint64_t                              scene_hash_ = 0;  // scene_fingerprint()
    // When this process started stepping, and what the processes before it spent (resume()).
    std::chrono::steady_clock::time_point      start_ = std::chrono::steady_clock::now();
    struct
    {
      double        wall_seconds = 0, linear_solve_seconds = 0;
      std::uint64_t symbolic_factorizations = 0, numeric_factorizations = 0;
    } earlier_;
  };
} // namespace ritr
