#pragma once
// What must hold after every step, checked and recorded rather than asserted: contact keeps
// a positive distance, no reference or deformed element inverts, and an r-adaptive step
// never ends above its start-of-step objective and keeps boundary nodes on their facets.
#include <ritr/contact/contact_potential.h>
#include <ritr/time/stepper.h>

#include <string>
#include <vector>

namespace ritr
{
  template <int dim>
  class InvariantChecker
  {
  public:
    // `contact` may be null (no contact, no distance to check).
    InvariantChecker(const SimplexMesh<dim> &mesh, const ContactPotential<dim> *contact)
      : mesh_(mesh), contact_(contact)
    {}

    // Fills the report's distance and element measures for the state reached by `result`,
    // and returns the invariants it violates, one line each.
    std::vector<std::string> check(StepResult &result) const;

  private:
    const SimplexMesh<dim>     &mesh_;
    const ContactPotential<dim> *contact_;
  };
} // namespace ritr
