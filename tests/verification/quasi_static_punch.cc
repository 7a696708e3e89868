// Quasi-static loading by a scripted obstacle: a rigid punch wider than the block moves down
// by 0.05 over five load steps onto a block clamped at its base (no gravity). Every load step
// converges, the block's top follows the punch to within the barrier's reach, and nothing
// inverts or penetrates. With r-ITR and the base's reference nodes sliding, the base nodes
// move along the base and stay on the clamped material points (x = u).
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes.h"

using namespace ritr;

namespace
{
  // A 1 x 0.5 neo-Hookean block clamped at its base, punched quasi-statically from above by a
  // rigid bar of width `width` centred at x = `centre`, moving down by `depth` over t in [0, 1].
  Scene punched_block(const double time_step, const double end_time, const double centre, const double width,
                      const std::string &depth, const bool sliding_base)
  {
    Scene s = test_support::basic_scene(2, "rectangle");
    s.mode                            = "static";
    s.time_step                       = time_step;
    s.end_time                        = end_time;
    s.bodies[0].geometry.lower        = {-0.5, 0};
    s.bodies[0].geometry.upper        = {0.5, 0.5};
    s.bodies[0].geometry.subdivisions = {8, 4};
    s.materials[0]                    = Material{MaterialModel::neo_hookean, 1e5, 0.3, 1000};
    DirichletScene base{{}, "1e-9 - y", "0;0", {}};
    base.sliding_reference_nodes = sliding_base;
    s.dirichlet.push_back(base);
    s.contact.enabled = true;
    s.contact.dhat    = 1e-3;
    ObstacleScene punch = test_support::plane_obstacle(2, {centre, 0.6 + 2e-3, 0}, {0, 1, 0});
    punch.type          = "punch";
    punch.size          = {width, 0.2, 1};
    punch.translation   = "0; -" + depth + " * t";
    s.obstacles.push_back(punch);
    return s;
  }
} // namespace

TEST(QuasiStaticPunch, TopFollowsThePunch)
{
  const Scene s = punched_block(0.2, 1.0, 0, 2, "0.05", false);
  Simulation<2> sim(s);
  for (unsigned int i = 0; i < s.n_steps(); ++i)
    {
      const StepReport r = sim.advance();
      EXPECT_GT(r.min_distance, 0.0);
      EXPECT_GT(r.min_deformed_jacobian, 0.0);
    }
  // Top nodes: pressed down by the punch travel minus the initial gap, up to dhat.
  for (unsigned int i = 0; i < sim.mesh().n_nodes(); ++i)
    if (sim.reference()[2 * i + 1] > 0.5 - 1e-9)
      {
        EXPECT_NEAR(sim.positions()[2 * i + 1] - 0.5, -(0.05 - 2e-3), 1e-3);
      }
}

TEST(QuasiStaticPunch, SlidingBaseNodesStayOnTheClampedMaterial)
{
  Scene s = punched_block(0.25, 0.5, 0.05, 0.25, "0.2", true);
  s.adaptivity.enabled = true;
  Simulation<2> sim(s);
  for (unsigned int i = 0; i < s.n_steps(); ++i)
    sim.advance();
  EXPECT_TRUE(sim.invariant_violations().empty()) << sim.invariant_violations().front();
  const SimplexMesh<2> &mesh  = sim.mesh();
  double                moved = 0;
  for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
    if (mesh.reference[2 * i + 1] < 1e-9)
      {
        EXPECT_EQ(sim.reference()[2 * i + 1], 0.0);  // on the base
        EXPECT_NEAR(sim.positions()[2 * i], sim.reference()[2 * i], 1e-12);
        EXPECT_NEAR(sim.positions()[2 * i + 1], 0.0, 1e-12);
        const double along = std::abs(sim.reference()[2 * i] - mesh.reference[2 * i]);
        if (std::abs(mesh.reference[2 * i]) > 0.5 - 1e-9)
          {
            EXPECT_EQ(along, 0.0);  // the base's ends are the block's corners
          }
        moved = std::max(moved, along);
      }
  EXPECT_GT(moved, 1e-4);
}
