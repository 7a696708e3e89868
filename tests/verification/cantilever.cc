// A plane-strain cantilever clamped at x = 0 and loaded by its own weight, small deflection:
// the tip deflection converges under uniform refinement to Euler-Bernoulli's
// q L^4 / (8 E' I), with q = rho g H, I = H^3 / 12 and E' = E / (1 - nu^2).
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.h"

using namespace ritr;

TEST(Cantilever, TipDeflectionConvergesToEulerBernoulli)
{
  const double L = 2.0, H = 0.1, E = 1e9, nu = 0.3, rho = 1000, g = 9.81;
  const double E_plane = E / (1 - nu * nu);
  const double expected = rho * g * H * std::pow(L, 4) / (8 * E_plane * std::pow(H, 3) / 12);

  std::vector<double> errors;
  for (unsigned int refinements = 0; refinements <= 3; ++refinements)
    {
      Scene s = test_support::basic_scene(2, "rectangle");
      s.mode                                  = "static";
      s.end_time = s.time_step                = 1.0;
      s.bodies[0].geometry.upper              = {L, H};
      s.bodies[0].geometry.subdivisions       = {40, 2};
      s.bodies[0].geometry.refinements        = refinements;
      s.materials[0]                          = Material{MaterialModel::linear, E, nu, rho};
      s.gravity                               = {0, -g, 0};
      s.dirichlet.push_back(DirichletScene{{}, "1e-9 - x", "0;0", {}});
      Simulation<2> sim(s);
      sim.advance();
      // Mean vertical displacement of the tip (x = L).
      double sum = 0;
      int    count = 0;
      for (unsigned int i = 0; i < sim.mesh().n_nodes(); ++i)
        if (sim.reference()[2 * i] > L - 1e-9)
          {
            sum += sim.positions()[2 * i + 1] - sim.reference()[2 * i + 1];
            ++count;
          }
      const double deflection = -sum / count;
      errors.push_back(std::abs(deflection - expected) / expected);
      std::cout << "refinements " << refinements << ": tip deflection " << deflection << " (Euler-Bernoulli "
                << expected << "), relative error " << errors.back() << std::endl;
    }
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], errors[i - 1]);
  EXPECT_LT(errors.back(), 0.03);
}
