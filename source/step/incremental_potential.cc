#include <ritr/step/incremental_potential.h>

namespace ritr
{
  template <int dim>
  void IncrementalPotential<dim>::begin_iteration(const Eigen::VectorXd &z)
  {
    if (!contact_)
      return;
    candidates_ = contact_->candidates_at(z);
    if (!adaptive_)
      return;
    const double d = contact_->active_minimum_distance(z, candidates_);
    contact_->set_stiffness(contact::update_barrier_stiffness(previous_distance_, d, contact_->stiffness(),
                                                              kappa_max_, bbox_diagonal_));
    previous_distance_ = d;
  }

  template <int dim>
  double IncrementalPotential<dim>::value(const Eigen::VectorXd &z)
  {
    double bulk = bulk_.value(body_positions(z), reference_);
    if (linear_term_.size() > 0)
      bulk += linear_term_.dot(z.head(linear_term_.size()));
    if (!std::isfinite(bulk) || !contact_)
      return bulk;
    return bulk + contact_->value(z, candidates_);
  }

  template <int dim>
  Eigen::VectorXd IncrementalPotential<dim>::bulk_gradient(const Eigen::VectorXd &z) const
  {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(z.size());
    Eigen::VectorXd gb = Eigen::VectorXd::Zero(reference_.size());
    bulk_.add_gradient(body_positions(z), reference_, gb);
    g.head(gb.size()) = gb;
    if (linear_term_.size() > 0)
      g.head(linear_term_.size()) += linear_term_;
    return g;
  }

  template <int dim>
  void IncrementalPotential<dim>::gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g)
  {
    g = bulk_gradient(z);
    if (contact_)
      contact_->add_gradient(z, candidates_, g);
  }

  template <int dim>
  void IncrementalPotential<dim>::hessian(const Eigen::VectorXd &z, Triplets &h, const bool project)
  {
    bulk_.add_hessian(body_positions(z), reference_, project, h);
    if (contact_)
      contact_->add_hessian(z, candidates_, h, project);
    // Obstacle vertices carry no mass; a unit diagonal keeps their (prescribed) rows regular.
    for (Eigen::Index i = reference_.size(); i < z.size(); ++i)
      h.emplace_back(i, i, 1.0);
  }

  template <int dim>
  double IncrementalPotential<dim>::max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz)
  {
    if (!contact_)
      return 1.0;
    candidates_ = contact_->candidates_along(z, dz);
    return contact_->max_step(z, dz);
  }

  template class IncrementalPotential<1>;
  template class IncrementalPotential<2>;
  template class IncrementalPotential<3>;
} // namespace ritr
