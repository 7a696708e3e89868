#include <ritr/step/step_objective.h>

namespace ritr
{
  template <int dim>
  void StepObjective<dim>::enable_adaptive_stiffness(const double kappa_max, const double bbox_diagonal)
  {
    adaptive_          = true;
    kappa_max_         = kappa_max;
    bbox_diagonal_     = bbox_diagonal;
    previous_distance_ = std::numeric_limits<double>::infinity();
  }

  template <int dim>
  void StepObjective<dim>::begin_iteration(const Eigen::VectorXd &z)
  {
    if (!terms_.has_contact())
      return;
    candidates_ = terms_.candidates_at(z);
    if (!adaptive_ || !barrier_)
      return;
    const double d = terms_.active_minimum_distance(z, candidates_);
    barrier_->set_stiffness(
      contact::update_barrier_stiffness(previous_distance_, d, barrier_->stiffness(), kappa_max_, bbox_diagonal_));
    previous_distance_ = d;
  }

  template <int dim>
  double StepObjective<dim>::value(const Eigen::VectorXd &z)
  {
    return terms_.energy(z, candidates_);
  }

  template <int dim>
  void StepObjective<dim>::gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g)
  {
    g = Eigen::VectorXd::Zero(z.size());
    terms_.add_energy_gradient(z, candidates_, g);
  }

  template <int dim>
  void StepObjective<dim>::hessian(const Eigen::VectorXd &z, Triplets &h, const bool project)
  {
    hessian_.clear();
    terms_.add_energy_hessian(z, candidates_, project, hessian_);
    hessian_.append_to(h);
    add_obstacle_diagonal(z, h);
  }

  template <int dim>
  void StepObjective<dim>::hessian_and_projection(const Eigen::VectorXd &z, Triplets &h, TripletChanges &projection)
  {
    hessian_.clear();
    terms_.add_energy_hessian_and_projection(z, candidates_, hessian_);
    hessian_.append_changes(h.size(), projection);
    hessian_.append_to(h);
    add_obstacle_diagonal(z, h);
  }

  template <int dim>
  void StepObjective<dim>::add_obstacle_diagonal(const Eigen::VectorXd &z, Triplets &h) const
  {
    // Obstacle vertices carry no mass; a unit diagonal keeps their (prescribed) rows regular.
    for (Eigen::Index i = terms_.reference().size(); i < z.size(); ++i)
      h.emplace_back(i, i, 1.0);
  }

  template <int dim>
  double StepObjective<dim>::max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz)
  {
    if (!terms_.has_contact())
      return 1.0;
    auto bound  = terms_.step_bound(z, dz);
    candidates_ = std::move(bound.candidates);
    return bound.fraction;
  }

  template class StepObjective<1>;
  template class StepObjective<2>;
  template class StepObjective<3>;
} // namespace ritr
