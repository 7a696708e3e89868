// The paper's ablations of r-ITR on small scenes (prm/verification/ritr):
//  - Fig. 8: without physical admissibility the bending beam's reference mesh degenerates,
//    with geometric and physical admissibility it stays well shaped (statics);
//  - Fig. 20: on the same beam r-ITR reaches a lower equilibrium energy than the fixed mesh
//    with the same vertex count, at every rung of a uniform refinement ladder;
//  - every r-ITR step: R ends at or below its start-of-step value, boundary sliding holds
//    to 1e-8, no reference or deformed element inverts (2D ball on spikes with friction).
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <map>

#include "ritr_scenes.h"

using namespace ritr;
using namespace ritr::test_support;

namespace
{
  // Smallest reference cell measure of the initial (uniform) mesh.
  template <int dim>
  double initial_min_measure(const Simulation<dim> &s)
  {
    double m = std::numeric_limits<double>::max();
    for (const auto &cell : s.mesh().cells)
      m = std::min(m, simplex_measure<dim, double>(cell_nodes<dim>(s.mesh().reference, cell)));
    return m;
  }
} // namespace

TEST(RitrAblations, PhysicalAdmissibilityKeepsTheBeamMeshWellShaped)
{
  Scene scene          = ritr_scene("bending_beam_2d.prm");
  scene.adaptivity.enabled = false;
  const double fixed   = static_energy(*run_scene<2>(scene));
  scene.adaptivity.enabled = true;
  std::map<std::string, std::pair<double, double>> result;  // energy, smallest cell / initial
  for (const std::string admissibility : {"none", "geometric", "physical", "both"})
    {
      scene.adaptivity.admissibility = admissibility;
      const auto s                   = run_scene<2>(scene);
      result[admissibility] = {static_energy(*s), s->history().back().min_reference_measure / initial_min_measure(*s)};
      std::cout << admissibility << ": energy " << result[admissibility].first << ", smallest cell / initial "
                << result[admissibility].second << " (fixed mesh energy " << fixed << ")" << std::endl;
    }
  // No admissibility: the joint minimisation runs away (inverted cells, unbounded energy).
  EXPECT_TRUE(result["none"].second <= 0 || result["none"].first < -1e3 * std::abs(fixed));
  // Both: well shaped (the measure barrier, active below a tenth of the initial smallest
  // cell, holds every cell near that threshold at worst) and better than the fixed mesh.
  EXPECT_GT(result["both"].second, 0.05);
  EXPECT_LT(result["both"].first, fixed);
}

TEST(RitrAblations, BeatsTheFixedMeshAtEveryRefinement)
{
  Scene scene = ritr_scene("bending_beam_2d.prm");
  for (const unsigned int refinement : {1u, 2u})
    {
      scene.bodies[0].geometry.subdivisions = {10 * refinement, 2 * refinement};
      scene.adaptivity.enabled = false;
      const double fixed       = static_energy(*run_scene<2>(scene));
      scene.adaptivity.enabled = true;
      const auto   adaptive    = run_scene<2>(scene);
      const double ritr        = static_energy(*adaptive);
      std::cout << adaptive->mesh().n_nodes() << " vertices: fixed " << fixed << ", r-ITR " << ritr << std::endl;
      EXPECT_LT(ritr, fixed);
    }
}

TEST(RitrAblations, EveryStepKeepsTheInvariants)
{
  Scene scene = read_scene(std::string(std::getenv("RITR_SOURCE_DIR")) + "/prm/verification/ball_on_spikes_2d.prm");
  scene.bodies[0].geometry.shape_refinements = 1;
  scene.end_time                             = 0.25;
  scene.adaptivity.enabled                   = true;
  scene.adaptivity.epsilon_r                 = 1e-4;
  scene.adaptivity.max_iterations            = 20;
  const auto s = run_scene<2>(scene);
  unsigned int outer = 0;
  for (const auto &r : s->history())
    {
      EXPECT_LE(r.energy, r.initial_objective) << "step " << r.step;
      EXPECT_LE(r.sliding_violation, 1e-8) << "step " << r.step;
      EXPECT_GT(r.min_distance, 0.0) << "step " << r.step;
      EXPECT_GT(r.min_reference_measure, 0.0) << "step " << r.step;
      EXPECT_GT(r.min_deformed_jacobian, 0.0) << "step " << r.step;
      outer += r.outer_iterations;
    }
  EXPECT_GT(outer, 0u);  // the mesh did adapt
  // The spikes touch the ball: some reference cells near the contact must have shrunk.
  EXPECT_LT(s->history().back().min_reference_measure, 0.9 * initial_min_measure(*s));
}
