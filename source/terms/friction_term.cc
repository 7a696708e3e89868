#include <ritr/terms/contact_barrier_term.h>
#include <ritr/terms/friction_term.h>

namespace ritr
{
  template <int dim>
  void FrictionTerm<dim>::lag(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates,
                              const Eigen::VectorXd &z_start, const double kappa)
  {
    friction_.clear();
    sources_.clear();
    unit_force_.clear();
    start_ = collisions_.vertices(z_start);
    if (coefficient_ <= 0 || dim == 1)
      return;
    const Eigen::MatrixXd V = collisions_.vertices(z_lagged);
    // One constraint at a time, so that each friction term keeps its weight's sources.
    for (const auto &c : collisions_.active_constraints(V, candidates))
      for (const auto &f : contact::build_friction_constraints<dim>({c}, V, collisions_.dhat(), kappa,
                                                                    collisions_.weights(), coefficient_))
        {
          friction_.push_back(f);
          sources_.push_back(collisions_.weight_sources(c));
          unit_force_.push_back(f.normal_force / collisions_.weights().weight(c));
        }
  }

  template <int dim>
  void FrictionTerm<dim>::set_reference(const Eigen::VectorXd &)
  {
    // The collision mesh's reference (set first by the sum) holds the new weights.
    for (std::size_t j = 0; j < friction_.size(); ++j)
      if (!sources_[j].empty())
        friction_[j].normal_force = unit_force_[j] * collisions_.weight_of(sources_[j]);
  }

  template <int dim>
  double FrictionTerm<dim>::value(const TermPoint &p) const
  {
    if (friction_.empty())
      return 0.0;
    return contact::friction_energy<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_);
  }

  template <int dim>
  void FrictionTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    if (friction_.empty())
      return;
    collisions_.scatter_gradient(
      contact::friction_gradient<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_), 1.0, g);
  }

  template <int dim>
  void FrictionTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    if (friction_.empty())
      return;
    collisions_.scatter_hessian(
      contact::friction_hessian<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_, project), 1.0,
      h.triplets());
  }

  template <int dim>
  void FrictionTerm<dim>::add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const
  {
    if (friction_.empty())
      return;
    const auto [exact, projected] =
      contact::friction_hessian_and_projection<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_);
    const std::size_t first = h.triplets().size();
    collisions_.scatter_hessian(exact, 1.0, h.triplets());  // one triplet per stencil entry, in order
    h.change_triplets(first, exact, projected, 1.0);
  }

  template <int dim>
  void FrictionTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block, const bool coupling,
                                                    ReferenceDerivativeAssembly<dim> &d) const
  {
    if (friction_.empty())
      return;
    // D = sum_j w_j(u) Dhat_j(x) with the lagged normal force per unit weight.
    const Eigen::MatrixXd V = collisions_.vertices(p.z);
    Triplets              hxu;
    for (std::size_t j = 0; j < friction_.size(); ++j)
      {
        auto unit         = friction_[j];
        unit.normal_force = unit_force_[j];
        const std::vector<contact::FrictionConstraint<dim>> one{unit};
        const double          energy = contact::friction_energy<dim>(one, V, start_, epsilon_v_times_h_);
        const Eigen::VectorXd full   = contact::friction_gradient<dim>(one, V, start_, epsilon_v_times_h_);
        std::vector<int>      stencil(unit.vertices.begin(), unit.vertices.begin() + unit.n_vertices);
        Eigen::VectorXd       gradient(stencil.size() * dim);
        for (std::size_t s = 0; s < stencil.size(); ++s)
          gradient.segment<dim>(s * dim) = full.segment<dim>(stencil[s] * dim);
        collisions_.add_weight_derivatives(sources_[j], energy, stencil, gradient, d.gu, d.huu.triplets(), hxu);
      }
    if (block != ReferenceBlock::following && !coupling)
      return;
    Triplets hessian;
    collisions_.scatter_hessian(contact::friction_hessian<dim>(friction_, V, start_, epsilon_v_times_h_, true), 1.0,
                                hessian);
    add_contact_state_blocks(p.u.size(), hessian, hxu, block, coupling, d.huu.triplets(), d.hxx.triplets(),
                             d.hxu.triplets());
    if (coupling)
      collisions_.scatter_gradient(contact::friction_gradient<dim>(friction_, V, start_, epsilon_v_times_h_), 1.0, d.gx);
  }

  template class FrictionTerm<1>;
  template class FrictionTerm<2>;
  template class FrictionTerm<3>;
} // namespace ritr
