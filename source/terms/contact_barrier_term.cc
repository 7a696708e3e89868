#include <ritr/terms/contact_barrier_term.h>

namespace ritr
{
  void add_contact_state_blocks(const Eigen::Index n_body, const Triplets &hessian, const Triplets &hxu,
                                const ReferenceBlock block, const bool coupling, Triplets &huu, Triplets &hxx,
                                Triplets &hxu_out)
  {
    if (block == ReferenceBlock::following)
      {
        // H_xu + H_ux + H_xx restricted to the body's nodes.
        for (const auto &t : hxu)
          if (t.row() < n_body)
            {
              huu.emplace_back(t.row(), t.col(), t.value());
              huu.emplace_back(t.col(), t.row(), t.value());
            }
        for (const auto &t : hessian)
          if (t.row() < n_body && t.col() < n_body)
            huu.push_back(t);
      }
    if (coupling)
      {
        hxx.insert(hxx.end(), hessian.begin(), hessian.end());
        hxu_out.insert(hxu_out.end(), hxu.begin(), hxu.end());
      }
  }

  template <int dim>
  double ContactBarrierTerm<dim>::value(const TermPoint &p) const
  {
    const Eigen::MatrixXd V = collisions_.vertices(p.z);
    return kappa_ * contact::barrier_energy<dim>(collisions_.active_constraints(V, p.candidates), V, collisions_.dhat(),
                                                 collisions_.weights());
  }

  template <int dim>
  Eigen::VectorXd ContactBarrierTerm<dim>::unscaled_gradient(const Eigen::VectorXd     &z,
                                                             const CollisionCandidates &candidates) const
  {
    const Eigen::MatrixXd V = collisions_.vertices(z);
    Eigen::VectorXd       g = Eigen::VectorXd::Zero(z.size());
    collisions_.scatter_gradient(contact::barrier_gradient<dim>(collisions_.active_constraints(V, candidates), V,
                                                                collisions_.dhat(), collisions_.weights()),
                                 1.0, g);
    return g;
  }

  template <int dim>
  void ContactBarrierTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    const Eigen::MatrixXd V = collisions_.vertices(p.z);
    collisions_.scatter_gradient(contact::barrier_gradient<dim>(collisions_.active_constraints(V, p.candidates), V,
                                                                collisions_.dhat(), collisions_.weights()),
                                 kappa_, g);
  }

  template <int dim>
  void ContactBarrierTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    const Eigen::MatrixXd V = collisions_.vertices(p.z);
    collisions_.scatter_hessian(contact::barrier_hessian<dim>(collisions_.active_constraints(V, p.candidates), V,
                                                              collisions_.dhat(), collisions_.weights(), project),
                                kappa_, h.triplets());
  }

  template <int dim>
  void ContactBarrierTerm<dim>::add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const
  {
    const Eigen::MatrixXd V           = collisions_.vertices(p.z);
    const auto            constraints = collisions_.active_constraints(V, p.candidates);
    const auto [exact, projected] =
      contact::barrier_hessian_and_projection<dim>(constraints, V, collisions_.dhat(), collisions_.weights());
    const std::size_t first = h.triplets().size();
    collisions_.scatter_hessian(exact, kappa_, h.triplets());  // one triplet per stencil entry, in order
    h.change_triplets(first, exact, projected, kappa_);
  }

  template <int dim>
  void ContactBarrierTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block,
                                                          const bool coupling, ReferenceDerivativeAssembly<dim> &d) const
  {
    const Eigen::MatrixXd V           = collisions_.vertices(p.z);
    const auto            constraints = collisions_.active_constraints(V, p.candidates);
    const auto            terms       = contact::unweighted_barrier_terms<dim>(constraints, V, collisions_.dhat());
    Triplets              hxu;
    for (std::size_t k = 0; k < constraints.size(); ++k)
      {
        const std::vector<int> stencil(constraints[k].vertices.begin(),
                                       constraints[k].vertices.begin() + constraints[k].n_vertices);
        collisions_.add_weight_derivatives(collisions_.weight_sources(constraints[k]), kappa_ * terms[k].value, stencil,
                                           kappa_ * terms[k].gradient, d.gu, d.huu.triplets(), hxu);
      }
    if (block != ReferenceBlock::following && !coupling)
      return;
    Triplets hessian;
    collisions_.scatter_hessian(
      contact::barrier_hessian<dim>(constraints, V, collisions_.dhat(), collisions_.weights(), true), kappa_, hessian);
    add_contact_state_blocks(p.u.size(), hessian, hxu, block, coupling, d.huu.triplets(), d.hxx.triplets(),
                             d.hxu.triplets());
    if (coupling)
      collisions_.scatter_gradient(contact::barrier_gradient<dim>(constraints, V, collisions_.dhat(), collisions_.weights()),
                                   kappa_, d.gx);
  }

  template class ContactBarrierTerm<1>;
  template class ContactBarrierTerm<2>;
  template class ContactBarrierTerm<3>;
} // namespace ritr
