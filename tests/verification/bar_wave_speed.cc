// A 1D elastic bar hitting a rigid wall: the contact lasts about 2 L / c with the
// longitudinal wave speed c = sqrt(E / rho) (the compression wave travels to the free end
// and back before the bar leaves the wall).
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.h"

using namespace ritr;

TEST(BarWaveSpeed, ContactTimeIsTwoLengthsOverWaveSpeed)
{
  const double L = 1.0, E = 1e6, rho = 1.0, v0 = 1.0;
  const double c = std::sqrt(E / rho), expected = 2 * L / c;  // 2 ms
  Scene s = test_support::basic_scene(1, "interval");
  s.bodies[0].geometry.lower        = {0.001};
  s.bodies[0].geometry.upper        = {0.001 + L};
  s.bodies[0].geometry.subdivisions = {400};
  s.bodies[0].initial_velocity      = "-1";
  s.materials[0]                    = Material{MaterialModel::linear, E, 0.0, rho};
  s.time_step                       = 1e-5;
  s.end_time                        = 4e-3;
  s.contact.enabled                 = true;
  s.contact.dhat                    = 1e-5;
  s.obstacles.push_back(test_support::plane_obstacle(1, {0, 0, 0}, {1, 0, 0}));
  Simulation<1> sim(s);

  double first_contact = -1, last_contact = -1;
  for (unsigned int i = 0; i < s.n_steps(); ++i)
    {
      sim.advance();
      if (sim.contact_forces().cwiseAbs().maxCoeff() > 1e-6 * rho * L * v0 * c)
        {
          if (first_contact < 0)
            first_contact = sim.time();
          last_contact = sim.time();
        }
    }
  ASSERT_GT(first_contact, 0);
  const double duration = last_contact - first_contact;
  std::cout << "contact duration " << duration << " s, 2L/c = " << expected << " s" << std::endl;
  EXPECT_NEAR(duration, expected, 0.1 * expected);
  // The bar leaves the wall moving away from it.
  EXPECT_GT(sim.velocities().mean(), 0.0);
}
