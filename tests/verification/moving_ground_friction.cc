// Friction from a moving obstacle: a block resting on a ground that moves sideways at speed
// V is dragged along with acceleration mu g until it reaches V (then it moves with the
// ground). Checks that lagged friction measures slip relative to scripted obstacles.
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.h"

using namespace ritr;

TEST(MovingGroundFriction, BlockIsDraggedAtMuGThenRidesAlong)
{
  const double g = 9.81, mu = 0.3, V = 1.0, h = 0.005;
  Scene s = test_support::basic_scene(2, "rectangle");
  s.bodies[0].geometry.lower        = {-0.1, 1e-3};
  s.bodies[0].geometry.upper        = {0.1, 0.101};
  s.bodies[0].geometry.subdivisions = {4, 2};
  s.materials[0]                    = Material{MaterialModel::neo_hookean, 1e6, 0.3, 1000};
  s.gravity                         = {0, -g, 0};
  s.time_step                       = h;
  s.end_time                        = 0.5;
  s.contact.enabled                 = true;
  s.contact.dhat                    = 1e-3;
  s.contact.friction_coefficient    = mu;
  s.contact.epsilon_v               = 1e-3;
  s.contact.friction_iterations     = 3;
  ObstacleScene ground = test_support::plane_obstacle(2, {0, 0, 0}, {0, 1, 0}, 40);
  ground.translation   = std::to_string(V) + " * t; 0";
  s.obstacles.push_back(ground);
  Simulation<2> sim(s);

  const double t_catch = V / (mu * g);  // 0.34 s
  for (unsigned int i = 0; i < s.n_steps(); ++i)
    {
      sim.advance();
      double vx = 0;
      for (unsigned int n = 0; n < sim.mesh().n_nodes(); ++n)
        vx += sim.velocities()[2 * n] / sim.mesh().n_nodes();
      const double t = sim.time();
      if (std::abs(t - 0.2) < 1e-9)
        {
          std::cout << "t = 0.2: block velocity " << vx << ", mu g t = " << mu * g * t << std::endl;
          EXPECT_NEAR(vx, mu * g * t, 0.03 * mu * g * t);
        }
      if (t > t_catch + 0.1)
        {
          EXPECT_NEAR(vx, V, 0.02 * V) << "at t = " << t;
        }
    }
}
