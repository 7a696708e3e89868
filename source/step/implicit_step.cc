#include <ritr/step/implicit_step.h>
#include <ritr/terms/friction_term.h>

#include <cmath>
#include <limits>

namespace ritr
{
  template <int dim>
  ImplicitStep<dim>::ImplicitStep(TermSum<dim> &terms, const CellMaterials<dim> &materials,
                                  const std::vector<bool> &kinematic, const ImplicitStepSettings &settings)
    : terms_(terms)
    , materials_(materials)
    , kinematic_(kinematic)
    , settings_(settings)
    , objective_(terms)
  {}

  template <int dim>
  typename ImplicitStep<dim>::Report ImplicitStep<dim>::solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z,
                                                                      const Eigen::VectorXd &targets,
                                                                      const bool             near_solution,
                                                                      const double           tolerance_scale,
                                                                      const unsigned int     iteration_cap)
  {
    terms_.set_reference(u);
    NewtonSettings newton = settings_.newton;
    newton.start_exact    = near_solution;
    newton.tolerance *= tolerance_scale;
    const bool capped = iteration_cap > 0 && iteration_cap < newton.max_iterations;
    if (capped)
      newton.max_iterations = iteration_cap;
    const NewtonResult r = newton_.minimize(objective_, z, kinematic_, targets, newton);
    // Stopped by the cap: the state is admissible (every accepted Newton step is), but only
    // once the prescribed entries have reached their targets.
    const bool at_cap = capped && r.status == NewtonStatus::iteration_limit && std::isfinite(r.energy) &&
                        prescribed_reached(z, targets);
    if (r.status != NewtonStatus::converged && !at_cap)
      throw ConvergenceError(r.failure);
    return {r.iterations, r.line_search_trials, r.energy, r.status == NewtonStatus::converged};
  }

  template <int dim>
  bool ImplicitStep<dim>::prescribed_reached(const Eigen::VectorXd &z, const Eigen::VectorXd &targets) const
  {
    for (std::size_t i = 0; i < kinematic_.size(); ++i)
      if (kinematic_[i] && z[i] != targets[i])
        return false;
    return true;
  }

  template <int dim>
  typename ImplicitStep<dim>::Report ImplicitStep<dim>::solve_start_of_step(const StepContext<dim> &step,
                                                                            Eigen::VectorXd        &z)
  {
    const Eigen::VectorXd &u = step.u_start;
    terms_.begin_step(step);
    terms_.set_reference(u);
    objective_.disable_adaptive_stiffness();
    auto *barrier  = terms_.template find<ContactBarrierTerm<dim>>();
    auto *friction = terms_.template find<FrictionTerm<dim>>();
    if (barrier)
      {
        const double diagonal = terms_.collision_mesh().bbox_diagonal(z);
        if (settings_.barrier_stiffness > 0)
          barrier->set_stiffness(settings_.barrier_stiffness);
        else
          {
            // IPC's rule balances the barrier's gradient against everything else's.
            const CollisionCandidates candidates = terms_.candidates_at(z);
            Eigen::VectorXd           others     = Eigen::VectorXd::Zero(z.size());
            terms_.add_energy_gradient(z, candidates, others, TermSum<dim>::Select::without_contact);
            Eigen::VectorXd barrier_gradient = barrier->unscaled_gradient(z, candidates);
            terms_.work_share().sum(barrier_gradient);  // this process's stencils only
            auto stiffness = contact::initial_barrier_stiffness(diagonal, terms_.collision_mesh().dhat(),
                                                                materials_.nodal_masses(u).mean(),
                                                                terms_.collision_mesh().mean_body_vertex_weight(), others,
                                                                barrier_gradient);
            if (!step.dynamic)
              {
                // Statics has no inertia, so IPC's mass-scaled bounds mean nothing there; the
                // cap at 100 times the lower bound shrinks with the cells (mass per unit
                // weight ~ h) and once held gaps at 1e-12, where Newton and CCD crawl. Without
                // it the doubling rule runs until the gaps stay open, and a load step starts as
                // stiff as the last one ended, instead of letting the gaps it opened close
                // again (doc/method.md, Barrier stiffness).
                stiffness.kappa_max = std::numeric_limits<double>::infinity();
                stiffness.kappa     = std::max(stiffness.kappa, step.barrier_stiffness);
              }
            barrier->set_stiffness(stiffness.kappa);
            objective_.enable_adaptive_stiffness(stiffness.kappa_max, diagonal);
          }
      }
    const unsigned int friction_iterations = friction ? settings_.friction_iterations : 1;
    Report             report;
    for (unsigned int f = 0; f < friction_iterations; ++f)
      {
        if (friction)
          friction->lag(z, terms_.candidates_at(z), barrier ? barrier->stiffness() : 0.0);
        const Report r = solve_on_mesh(u, z, step.targets);
        report.iterations += r.iterations;
        report.line_search_trials += r.line_search_trials;
        report.energy = r.energy;
      }
    objective_.disable_adaptive_stiffness();
    return report;
  }

  template class ImplicitStep<1>;
  template class ImplicitStep<2>;
  template class ImplicitStep<3>;
} // namespace ritr
