// A block on an incline (gravity tilted by theta over a horizontal ground): it sticks when
// mu > tan(theta), and otherwise slides with acceleration g (sin theta - mu cos theta).
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.h"

using namespace ritr;

namespace
{
  // Mean tangential displacement and velocity of the block after `duration` seconds.
  std::pair<double, double> slide(const double mu, const double theta, const double duration)
  {
    const double g = 9.81;
    Scene s = test_support::basic_scene(2, "rectangle");
    s.bodies[0].geometry.lower        = {0, 1e-3};
    s.bodies[0].geometry.upper        = {0.2, 0.101};
    s.bodies[0].geometry.subdivisions = {4, 2};
    s.materials[0]                    = Material{MaterialModel::neo_hookean, 1e6, 0.3, 1000};
    s.gravity                         = {g * std::sin(theta), -g * std::cos(theta), 0};
    s.time_step                       = 0.01;
    s.end_time                        = duration;
    s.contact.enabled                 = true;
    s.contact.dhat                    = 1e-3;
    s.contact.friction_coefficient    = mu;
    s.contact.epsilon_v               = 1e-4;
    s.contact.friction_iterations     = 4;
    s.solver.newton_tolerance         = 1e-6;
    s.obstacles.push_back(test_support::plane_obstacle(2, {0, 0, 0}, {0, 1, 0}));
    Simulation<2> sim(s);
    for (unsigned int i = 0; i < s.n_steps(); ++i)
      sim.advance();
    double dx = 0, vx = 0;
    for (unsigned int i = 0; i < sim.mesh().n_nodes(); ++i)
      {
        dx += sim.positions()[2 * i] - sim.reference()[2 * i];
        vx += sim.velocities()[2 * i];
      }
    return {dx / sim.mesh().n_nodes(), vx / sim.mesh().n_nodes()};
  }
} // namespace

TEST(Incline, SticksWhenFrictionExceedsSlope)
{
  const double theta = 0.3;  // tan = 0.309
  const auto [dx, vx] = slide(0.5, theta, 0.5);
  std::cout << "mu = 0.5: displacement " << dx << ", velocity " << vx << std::endl;
  EXPECT_LT(std::abs(vx), 2e-3);
  EXPECT_LT(std::abs(dx), 1e-3);
}

TEST(Incline, SlidesWithCoulombAcceleration)
{
  const double theta = 0.5, mu = 0.2, g = 9.81;
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  const auto [dx, vx] = slide(mu, theta, 0.5);
  std::cout << "mu = 0.2: velocity " << vx << " (expected " << a * 0.5 << "), displacement " << dx
            << std::endl;
  EXPECT_NEAR(vx, a * 0.5, 0.03 * a * 0.5);
  // Implicit Euler: s_n = h^2 a n (n + 1) / 2.
  const double h = 0.01, n = 50;
  EXPECT_NEAR(dx, h * h * a * n * (n + 1) / 2, 0.05 * h * h * a * n * (n + 1) / 2);
}
