// Quasi-static loading by a scripted obstacle: a rigid punch wider than the block moves down
// by 0.05 over five load steps onto a block clamped at its base (no gravity). Every load step
// converges, the block's top follows the punch to within the barrier's reach, and nothing
// inverts or penetrates.
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include "scenes.h"

using namespace ritr;

TEST(QuasiStaticPunch, TopFollowsThePunch)
{
  Scene s = test_support::basic_scene(2, "rectangle");
  s.mode                            = "static";
  s.time_step                       = 0.2;
  s.end_time                        = 1.0;
  s.bodies[0].geometry.lower        = {-0.5, 0};
  s.bodies[0].geometry.upper        = {0.5, 0.5};
  s.bodies[0].geometry.subdivisions = {8, 4};
  s.materials[0]                    = Material{MaterialModel::neo_hookean, 1e5, 0.3, 1000};
  s.dirichlet.push_back(DirichletScene{{}, "1e-9 - y", "0;0", {}});
  s.contact.enabled = true;
  s.contact.dhat    = 1e-3;
  ObstacleScene punch = test_support::plane_obstacle(2, {0, 0.6 + 2e-3, 0}, {0, 1, 0});
  punch.type          = "punch";
  punch.size          = {2, 0.2, 1};
  punch.translation   = "0; -0.05 * t";
  s.obstacles.push_back(punch);
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
