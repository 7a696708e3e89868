#include <ritr/common/wall_clock.h>
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/time/simulation.h>

#include <chrono>

namespace ritr
{
  template <int dim>
  Simulation<dim>::~Simulation() = default;

  template <int dim>
  Simulation<dim>::Simulation(const Scene &scene, const WorkShare &share)
    : problem_(make_problem<dim>(scene, share))
    , scene_(problem_->scene)
    , mesh_(problem_->mesh)
    , obstacles_(problem_->obstacles)
    , terms_(*problem_->terms)
    , invariants_(problem_->mesh, problem_->collisions.get(), problem_->kinematic, problem_->sliding_dirichlet_nodes)
    , u_(problem_->initial_reference)
    , x_(problem_->initial_positions)
    , v_(problem_->initial_velocity)
    , obstacle_positions_(problem_->initial_obstacle_positions)
    , time_(scene_.start_time)
  {
    NewtonMonitor monitor;
    if (scene_.solver.newton_log)
      monitor = [this](const NewtonIterationRecord &record, const Eigen::VectorXd &z) {
        log_newton_iteration(record, z);
      };
    stepper_ = make_stepper(*problem_, monitor);
    scene_hash_ = scene_fingerprint(scene_.parameter_listing);
  }

  template <int dim>
  Eigen::VectorXd Simulation<dim>::state() const
  {
    Eigen::VectorXd z(x_.size() + obstacle_positions_.size());
    z << x_, obstacle_positions_;
    return z;
  }

  template <int dim>
  StepReport Simulation<dim>::advance()
  {
    const auto   start = std::chrono::steady_clock::now();
    const double h     = scene_.time_step;
    StepContext<dim> context;
    context.step      = step_ + 1;
    // The last step lands on the end time, not on an accumulation of rounded steps.
    context.time      = step_ + 1 == scene_.n_steps() ? scene_.end_time : time_ + h;
    context.time_step = h;
    context.dynamic   = scene_.dynamic();
    context.gravity   = problem_->gravity(context.time);
    context.u_start   = u_;
    context.z_start   = state();
    context.v_start   = v_;
    context.targets   = problem_->targets(context.time);
    context.barrier_stiffness = barrier_stiffness_;

    StepResult result = stepper_->step(context);
    u_                  = result.u;
    x_                  = result.z.head(u_.size());
    obstacle_positions_ = result.z.tail(obstacle_positions_.size());
    v_                  = result.v;
    time_               = context.time;
    ++step_;
    result.report.step = context.step;
    result.report.time = context.time;
    // The stiffness the step's first solve settled on (later solves of the step keep it).
    if (const auto *barrier = terms_.template find<ContactBarrierTerm<dim>>())
      barrier_stiffness_ = barrier->stiffness();
    for (auto &violation : invariants_.check(result, context.targets))
      invariant_violations_.push_back(std::move(violation));
    result.report.wall_seconds = seconds_since(start);
    history_.push_back(result.report);
    return result.report;
  }

  template <int dim>
  Eigen::VectorXd Simulation<dim>::contact_forces() const
  {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(x_.size());
    if (!terms_.has_contact())
      return f;
    Eigen::VectorXd       g = Eigen::VectorXd::Zero(x_.size() + obstacle_positions_.size());
    const Eigen::VectorXd z = state();
    terms_.add_energy_gradient(z, terms_.candidates_at(z), g, TermSum<dim>::Select::contact);
    const double weight = scene_.dynamic() ? scene_.time_step * scene_.time_step : 1.0;
    return -g.head(x_.size()) / weight;
  }

  template class Simulation<1>;
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace ritr
