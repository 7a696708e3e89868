// Free fall under gravity: with no contact and uniform gravity the body translates rigidly,
// so implicit Euler gives v_n = v_0 + n h g and x_n = x_0 + n h v_0 + h^2 g n (n + 1) / 2
// exactly, in every dimension.
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include "scenes.h"

using namespace ritr;

template <int dim>
void check_free_fall()
{
  Scene s = test_support::basic_scene(dim, dim == 1 ? "interval" : dim == 2 ? "rectangle" : "box");
  s.bodies[0].geometry.subdivisions = {3, 2, 2};
  s.bodies[0].initial_velocity      = dim == 1 ? "0.5" : dim == 2 ? "0.5;2" : "0.5;2;-1";
  s.gravity                         = {-1.0, -9.81, 3.0};
  s.time_step                       = 0.02;
  s.end_time                        = 0.4;
  s.solver.newton_tolerance         = 1e-10;
  Simulation<dim> sim(s);
  const std::vector<double> v0{0.5, 2, -1};
  const unsigned int        n = s.n_steps();
  for (unsigned int i = 0; i < n; ++i)
    sim.advance();
  const double h = s.time_step;
  for (unsigned int node = 0; node < sim.mesh().n_nodes(); ++node)
    for (int k = 0; k < dim; ++k)
      {
        const double g = s.gravity[k];
        EXPECT_NEAR(sim.velocities()[node * dim + k], v0[k] + n * h * g, 1e-8);
        EXPECT_NEAR(sim.positions()[node * dim + k] - sim.reference()[node * dim + k],
                    n * h * v0[k] + h * h * g * n * (n + 1) / 2.0, 1e-8);
      }
}

TEST(FreeFall, ImplicitEuler1D) { check_free_fall<1>(); }
TEST(FreeFall, ImplicitEuler2D) { check_free_fall<2>(); }
TEST(FreeFall, ImplicitEuler3D) { check_free_fall<3>(); }
