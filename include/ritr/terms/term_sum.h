#pragma once
// The sum of a step's terms, which feeds both solves: the incremental potential E(z; u) of
// the terms that depend on the state (the inner solve over z at a fixed mesh) and the r-ITR
// objective R(z, u) of all of them (the outer solve over u). It also holds the collision
// geometry the contact terms share (none without contact): setting the reference mesh sets
// its weights, and the candidates an evaluation looks at are built from it.
#include <ritr/parallel/work_share.h>
#include <ritr/terms/energy_term.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ritr
{
  template <int dim>
  class TermSum
  {
  public:
    // `collisions` (null: no contact) must outlive the sum, as must the mesh.
    TermSum(const SimplexMesh<dim> &mesh, CollisionMesh<dim> *collisions);

    // Adds a term, built in place; terms are summed in the order they were added.
    template <typename Term, typename... Args>
    Term &add(Args &&...args)
    {
      auto  term = std::make_unique<Term>(std::forward<Args>(args)...);
      Term &ref  = *term;
      terms_.push_back(std::move(term));
      return ref;
    }
    // The term of type Term, null if the sum has none.
    template <typename Term>
    Term *find() const
    {
      for (const auto &t : terms_)
        if (auto *found = dynamic_cast<Term *>(t.get()))
          return found;
      return nullptr;
    }

    void begin_step(const StepContext<dim> &context);
    // The reference mesh of the evaluations that follow (a no-op if it is the current one).
    void set_reference(const Eigen::VectorXd &u);
    const Eigen::VectorXd &reference() const { return reference_; }

    // A run shared among processes: the cell terms were built on this process's cells, the
    // candidates below are this process's stencils, and energies, energy gradients, step
    // bounds and distances are reduced over the processes (Hessians stay this process's
    // part). The share must outlive the sum; without one the sum is serial.
    void              share_work(const WorkShare &share) { share_ = &share; }
    const WorkShare  &work_share() const { return share_ ? *share_ : serial_; }

    bool                      has_contact() const { return collisions_ != nullptr; }
    const CollisionMesh<dim> &collision_mesh() const { return *collisions_; }
    // Empty without contact; shared among processes, this process's.
    CollisionCandidates candidates_at(const Eigen::VectorXd &z) const;
    CollisionCandidates candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;
    // The smallest distance of the candidates' pairs within dhat (over all processes).
    double active_minimum_distance(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;

    // Which terms a gradient sums.
    enum class Select
    {
      all,
      contact,
      without_contact
    };
    // E(z; u): the terms that depend on the state; +infinity where one is inadmissible.
    double energy(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;
    void   add_energy_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates, Eigen::VectorXd &g,
                               Select select = Select::all) const;
    void   add_energy_hessian(const Eigen::VectorXd &z, const CollisionCandidates &candidates, bool project,
                              MatrixAssembly<dim> &h) const;
    // The exact Hessian of E with the projection's changes (energy_term.h).
    void   add_energy_hessian_and_projection(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                             MatrixAssembly<dim> &h) const;
    // Smallest of the terms' admissible fractions of the step dz (over all processes), with
    // candidates_along(z, dz): one broad phase serves both the bound and the energy along
    // the step.
    struct StepBound
    {
      double              fraction;
      CollisionCandidates candidates;
    };
    StepBound step_bound(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;
    double    max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const { return step_bound(z, dz).fraction; }

    // R(z, u): every term.
    double objective(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;
    // Each term's value at (z, u), in the order they are summed.
    std::vector<std::pair<std::string, double>> values(const Eigen::VectorXd &z,
                                                       const CollisionCandidates &candidates) const;
    // R's derivatives at (z, u): g_u and H_uu always, with `coupling` also g_z and the z-z
    // and z-u blocks (energy_term.h).
    struct ReferenceDerivatives
    {
      Eigen::VectorXd gu, gx;
      Triplets        huu, hxx, hxu;
    };
    ReferenceDerivatives reference_derivatives(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                               ReferenceBlock block, bool coupling) const;
    // dR/du at fixed z alone (first-order outer solves); `without_mesh_terms` leaves out
    // the terms of the reference mesh alone.
    Eigen::VectorXd reference_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                       bool without_mesh_terms = false) const;

    const SimplexMesh<dim> &mesh() const { return mesh_; }

  private:
    double sum(const Eigen::VectorXd &z, const CollisionCandidates &candidates, bool state_terms_only) const;

    // This process's part of the candidates.
    CollisionCandidates owned(CollisionCandidates candidates) const;

    const SimplexMesh<dim>                        &mesh_;
    CollisionMesh<dim>                            *collisions_;
    const WorkShare                               *share_ = nullptr;
    WorkShare                                      serial_;
    std::vector<std::unique_ptr<EnergyTerm<dim>>> terms_;
    Eigen::VectorXd                                reference_;
  };
} // namespace ritr
