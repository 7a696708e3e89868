#pragma once
// What must hold after every step, checked and recorded rather than asserted: contact keeps
// a positive distance, no reference or deformed element inverts, prescribed entries are at
// their targets (a sliding Dirichlet node's at the material point it carries), and an
// r-adaptive step never ends above its start-of-step objective and keeps boundary nodes on
// their facets.
#include <ritr/contact/collision_mesh.h>
#include <ritr/time/stepper.h>

#include <string>
#include <vector>

namespace ritr
{
  template <int dim>
  class InvariantChecker
  {
  public:
    // `collisions` may be null (no contact, no distance to check); `kinematic` flags the
    // prescribed state entries, `sliding_dirichlet_nodes` the nodes whose targets follow u.
    InvariantChecker(const SimplexMesh<dim> &mesh, const CollisionMesh<dim> *collisions,
                     const std::vector<bool>                                  &kinematic,
                     const std::vector<std::pair<unsigned int, unsigned int>> &sliding_dirichlet_nodes);

    // Fills the report's distance and element measures for the state reached by `result`,
    // and returns the invariants it violates, one line each; `targets` are the step's
    // prescribed entries (at the initial reference).
    std::vector<std::string> check(StepResult &result, const Eigen::VectorXd &targets) const;

  private:
    const SimplexMesh<dim>     &mesh_;
    const CollisionMesh<dim>   *collisions_;
    const std::vector<bool>    &kinematic_;
    std::vector<int>            sliding_entries_;
  };
} // namespace ritr
