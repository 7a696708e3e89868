#pragma once
// Runs the r-ITR verification scenes of prm/verification/ritr in-process, with the
// adaptivity switches of each ablation set in code.
#include <ritr/scene/parameters.h>
#include <ritr/terms/body_force_term.h>
#include <ritr/terms/elasticity_term.h>
#include <ritr/time/simulation.h>

#include "test_paths.h"

#include <memory>
#include <string>

namespace ritr::test_support
{
  inline Scene ritr_scene(const std::string &name)
  {
    return read_scene(test_support::source_dir() + "/prm/verification/ritr/" + name);
  }

  // Builds the simulation and advances it through every step of the scene.
  template <int dim>
  std::unique_ptr<Simulation<dim>> run_scene(const Scene &scene)
  {
    auto simulation = std::make_unique<Simulation<dim>>(scene);
    for (unsigned int i = 0; i < scene.n_steps(); ++i)
      simulation->advance();
    return simulation;
  }

  // Potential energy Psi - gravity work of the final state (statics: the equilibrium energy),
  // the simulation's own terms as its last step left them.
  template <int dim>
  double static_energy(const Simulation<dim> &s)
  {
    const TermPoint p{s.positions(), s.reference(), {}};
    return s.terms().template find<ElasticityTerm<dim>>()->value(p) +
           s.terms().template find<BodyForceTerm<dim>>()->value(p);
  }
} // namespace ritr::test_support
