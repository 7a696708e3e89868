#include <ritr/step/implicit_step.h>

namespace ritr
{
  template <int dim>
  ImplicitStep<dim>::ImplicitStep(BulkEnergy<dim> &bulk, ContactPotential<dim> *contact,
                                  const std::vector<bool> &kinematic, const ImplicitStepSettings &settings)
    : bulk_(bulk)
    , contact_(contact)
    , kinematic_(kinematic)
    , settings_(settings)
    , reference_(bulk.mesh().reference)
    , potential_(bulk, contact, reference_)
  {}

  template <int dim>
  typename ImplicitStep<dim>::Report ImplicitStep<dim>::solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z,
                                                                      const Eigen::VectorXd &targets,
                                                                      const bool near_solution)
  {
    reference_ = u;
    if (contact_)
      contact_->set_reference(u);
    NewtonSettings newton = settings_.newton;
    newton.start_exact    = near_solution;
    const NewtonResult r  = newton_.minimize(potential_, z, kinematic_, targets, newton);
    if (!r.converged)
      throw ConvergenceError(r.failure);
    return {r.iterations, r.line_search_trials, r.energy};
  }

  template <int dim>
  typename ImplicitStep<dim>::Report ImplicitStep<dim>::solve_start_of_step(const StepContext<dim> &step,
                                                                            Eigen::VectorXd        &z)
  {
    const Eigen::VectorXd &u = step.u_start;
    potential_.disable_adaptive_stiffness();
    unsigned int friction_iterations = 1;
    if (contact_)
      {
        reference_ = u;
        contact_->set_reference(u);
        const double diagonal = contact_->bbox_diagonal(z);
        if (settings_.barrier_stiffness > 0)
          contact_->set_stiffness(settings_.barrier_stiffness);
        else
          {
            const auto stiffness = contact::initial_barrier_stiffness(
              diagonal, settings_.dhat, bulk_.nodal_masses(u).mean(), potential_.bulk_gradient(z),
              contact_->barrier_gradient(z, contact_->candidates_at(z)));
            contact_->set_stiffness(stiffness.kappa);
            potential_.enable_adaptive_stiffness(stiffness.kappa_max, diagonal);
          }
        friction_iterations = settings_.friction_iterations;
      }
    Report report;
    for (unsigned int f = 0; f < friction_iterations; ++f)
      {
        if (contact_)
          contact_->update_friction(z, contact_->candidates_at(z), step.z_start);
        const Report r = solve_on_mesh(u, z, step.targets);
        report.iterations += r.iterations;
        report.line_search_trials += r.line_search_trials;
        report.energy = r.energy;
      }
    potential_.disable_adaptive_stiffness();
    return report;
  }

  template class ImplicitStep<1>;
  template class ImplicitStep<2>;
  template class ImplicitStep<3>;
} // namespace ritr
