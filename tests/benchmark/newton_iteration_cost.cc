// One Newton iteration against one CHOLMOD factorization + solve of the same Hessian, on the
// 2D scale scene (about 100K vertices, contact with the ground): everything a Newton
// iteration does besides the linear solve (assembly, contact, CCD, line search) should cost
// at most as much as the solve itself, i.e. a ratio <= 2.
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <chrono>

#include "run_ritr.h"

using namespace ritr;

TEST(NewtonIterationCost, AgainstFactorizationAndSolve)
{
  Scene s    = read_scene(test_support::source_dir() + "/prm/benchmark/scale_2d.prm");
  s.end_time = 2 * s.time_step;
  Simulation<2> sim(s);
  const auto    start = std::chrono::steady_clock::now();
  unsigned int  iterations = 0;
  for (unsigned int i = 0; i < s.n_steps(); ++i)
    iterations += sim.advance().newton_iterations;
  const double total  = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double linear = sim.newton_solver().seconds_in_linear_solves();
  const unsigned int factorizations = sim.newton_solver().linear_solver().n_factorizations();
  const double ratio = (total / factorizations) / (linear / factorizations);
  std::cout << "| vertices | Newton iterations | factorizations | s per iteration | s per factorization+solve | ratio |\n"
            << "| " << sim.mesh().n_nodes() << " | " << iterations << " | " << factorizations << " | "
            << total / factorizations << " | " << linear / factorizations << " | " << ratio << " |" << std::endl;
  EXPECT_LT(ratio, 2.0);
}
