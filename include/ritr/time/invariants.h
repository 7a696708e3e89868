#pragma once
// What must hold after every step, checked and recorded rather than asserted: contact keeps
// a positive distance, no reference or deformed element inverts, and an r-adaptive step
// never ends above its start-of-step objective and keeps boundary nodes on their facets.
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
    // `collisions` may be null (no contact, no distance to check).
    InvariantChecker(const SimplexMesh<dim> &mesh, const CollisionMesh<dim> *collisions)
      : mesh_(mesh), collisions_(collisions)
    {}

    // Fills the report's distance and element measures for the state reached by `result`,
    // and returns the invariants it violates, one line each.
    std::vector<std::string> check(StepResult &result) const;

  private:
    const SimplexMesh<dim>     &mesh_;
    const CollisionMesh<dim>   *collisions_;
  };
} // namespace ritr
