#include <ritr/terms/term_sum.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ritr
{
  template <int dim>
  TermSum<dim>::TermSum(const SimplexMesh<dim> &mesh, CollisionMesh<dim> *collisions)
    : mesh_(mesh)
    , collisions_(collisions)
  {}

  template <int dim>
  void TermSum<dim>::begin_step(const StepContext<dim> &context)
  {
    reference_.resize(0);  // what the terms derived from the mesh belongs to the last step
    for (const auto &t : terms_)
      t->begin_step(context);
  }

  template <int dim>
  void TermSum<dim>::set_reference(const Eigen::VectorXd &u)
  {
    // Re-locating the transfer's quadrature is the expensive part of a new mesh, and the
    // outer solve asks for the mesh it already has at every iteration.
    if (reference_.size() == u.size() && reference_ == u)
      return;
    reference_ = u;
    if (collisions_)
      collisions_->set_reference(u);  // the contact terms' weights come from here
    for (const auto &t : terms_)
      t->set_reference(u);
  }

  template <int dim>
  CollisionCandidates TermSum<dim>::owned(CollisionCandidates candidates) const
  {
    const WorkShare &share = work_share();
    if (share.distributed())
      candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                      [&](const contact::Candidate &c) { return !share.owns(c); }),
                       candidates.end());
    return candidates;
  }

  template <int dim>
  CollisionCandidates TermSum<dim>::candidates_at(const Eigen::VectorXd &z) const
  {
    return collisions_ ? owned(collisions_->candidates_at(z)) : CollisionCandidates{};
  }

  template <int dim>
  CollisionCandidates TermSum<dim>::candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    return collisions_ ? owned(collisions_->candidates_along(z, dz)) : CollisionCandidates{};
  }

  template <int dim>
  double TermSum<dim>::active_minimum_distance(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const
  {
    return work_share().min(collisions_ ? collisions_->active_minimum_distance(z, candidates) :
                                          std::numeric_limits<double>::infinity());
  }

  template <int dim>
  double TermSum<dim>::sum(const Eigen::VectorXd &z, const CollisionCandidates &candidates, const bool state_terms_only) const
  {
    const TermPoint p{z, reference_, candidates};
    double          total = 0;
    for (const auto &t : terms_)
      {
        if (state_terms_only && !t->depends_on_state())
          continue;
        total += t->value(p);
        if (!std::isfinite(total))
          return std::numeric_limits<double>::infinity();
      }
    return total;
  }

  template <int dim>
  double TermSum<dim>::energy(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const
  {
    return work_share().sum(sum(z, candidates, true));
  }

  template <int dim>
  double TermSum<dim>::objective(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const
  {
    return work_share().sum(sum(z, candidates, false));
  }

  template <int dim>
  std::vector<std::pair<std::string, double>> TermSum<dim>::values(const Eigen::VectorXd     &z,
                                                                   const CollisionCandidates &candidates) const
  {
    const TermPoint                              p{z, reference_, candidates};
    std::vector<std::pair<std::string, double>> v;
    for (const auto &t : terms_)
      v.emplace_back(t->name(), work_share().sum(t->value(p)));
    return v;
  }

  template <int dim>
  void TermSum<dim>::add_energy_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                         Eigen::VectorXd &g, const Select select) const
  {
    const TermPoint p{z, reference_, candidates};
    const auto      add = [&](Eigen::VectorXd &to) {
      for (const auto &t : terms_)
        if (t->depends_on_state() && (select == Select::all || (select == Select::contact) == t->is_contact()))
          t->add_gradient(p, to);
    };
    if (!work_share().distributed())
      return add(g);
    Eigen::VectorXd part = Eigen::VectorXd::Zero(g.size());
    add(part);
    work_share().sum(part);
    g += part;
  }

  template <int dim>
  void TermSum<dim>::add_energy_hessian(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                        const bool project, MatrixAssembly<dim> &h) const
  {
    const TermPoint p{z, reference_, candidates};
    for (const auto &t : terms_)
      if (t->depends_on_state())
        t->add_hessian(p, project, h);
  }

  template <int dim>
  void TermSum<dim>::add_energy_hessian_and_projection(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                                       MatrixAssembly<dim> &h) const
  {
    const TermPoint p{z, reference_, candidates};
    for (const auto &t : terms_)
      if (t->depends_on_state())
        t->add_hessian_and_projection(p, h);
  }

  template <int dim>
  typename TermSum<dim>::StepBound TermSum<dim>::step_bound(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    // Every process bounds the step over all pairs (CCD is cheap beside the broad phase) and
    // keeps its own share of them for the energy.
    CollisionCandidates along    = collisions_ ? collisions_->candidates_along(z, dz) : CollisionCandidates{};
    double              fraction = 1.0;
    for (const auto &t : terms_)
      fraction = std::min(fraction, t->max_step(z, dz, along));
    return {work_share().min(fraction), owned(std::move(along))};
  }

  template <int dim>
  typename TermSum<dim>::ReferenceDerivatives TermSum<dim>::reference_derivatives(const Eigen::VectorXd     &z,
                                                                                  const CollisionCandidates &candidates,
                                                                                  const ReferenceBlock       block,
                                                                                  const bool coupling) const
  {
    const TermPoint                  p{z, reference_, candidates};
    ReferenceDerivativeAssembly<dim> assembly(mesh_.cells);
    assembly.gu = Eigen::VectorXd::Zero(reference_.size());
    if (coupling)
      assembly.gx = Eigen::VectorXd::Zero(z.size());
    for (const auto &t : terms_)
      t->add_reference_derivatives(p, block, coupling, assembly);
    ReferenceDerivatives d;
    d.gu  = std::move(assembly.gu);
    d.gx  = std::move(assembly.gx);
    d.huu = assembly.huu.to_triplets();
    if (coupling)
      {
        d.hxx = assembly.hxx.to_triplets();
        d.hxu = assembly.hxu.to_triplets();
      }
    return d;
  }

  template <int dim>
  Eigen::VectorXd TermSum<dim>::reference_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                                   const bool without_mesh_terms) const
  {
    const TermPoint                  p{z, reference_, candidates};
    ReferenceDerivativeAssembly<dim> assembly(mesh_.cells);
    assembly.gu = Eigen::VectorXd::Zero(reference_.size());
    assembly.huu.use_cell_blocks();  // where the terms without a gradient of their own leave H_uu
    for (const auto &t : terms_)
      if (!without_mesh_terms || t->depends_on_state())
        t->add_reference_gradient(p, assembly);
    return std::move(assembly.gu);
  }

  template class TermSum<1>;
  template class TermSum<2>;
  template class TermSum<3>;
} // namespace ritr
