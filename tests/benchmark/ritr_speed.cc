// r-ITR against fixed meshes on the 2D ball on spikes (prm/verification/ball_on_spikes_2d):
// per-step wall time of r-ITR on a coarse mesh, of the fixed mesh with the same vertices,
// and of fixed meshes refined uniformly to about 15x and 60x the vertices (the 30x
// lies between these rungs of the refinement ladder), with r-ITR's time split. All runs
// happen in this process one after another, so the printed ratios share one machine state.
#include <gtest/gtest.h>

#include <iostream>

#include "ritr_scenes.h"

using namespace ritr;
using namespace ritr::test_support;

namespace
{
  struct Timing
  {
    unsigned int vertices = 0;
    double       seconds_per_step = 0, inner = 0, transfer = 0, outer = 0;
    double       outer_iterations = 0, inner_iterations = 0;
  };

  Timing run(Scene scene, const unsigned int refinements, const bool adaptive)
  {
    scene.bodies[0].geometry.shape_refinements = refinements;
    scene.adaptivity.enabled                   = adaptive;
    scene.adaptivity.epsilon_r                 = 1e-4;
    scene.adaptivity.max_iterations            = 20;
    const auto s = run_scene<2>(scene);
    Timing     t;
    t.vertices   = s->mesh().n_nodes();
    const double n = s->history().size();
    for (const auto &r : s->history())
      {
        t.seconds_per_step += r.wall_seconds / n;
        t.inner += r.inner_seconds / n;
        t.transfer += r.transfer_seconds / n;
        t.outer += r.outer_solve_seconds / n;
        t.outer_iterations += r.outer_iterations / n;
        t.inner_iterations += r.newton_iterations / n;
      }
    return t;
  }
} // namespace

TEST(RitrSpeed, BallOnSpikesAgainstFixedMeshes)
{
  Scene scene    = read_scene(test_support::source_dir() + "/prm/verification/ball_on_spikes_2d.prm");
  scene.end_time = 0.3;
  const Timing ritr   = run(scene, 1, true);
  const Timing same   = run(scene, 1, false);
  const Timing fine15 = run(scene, 3, false);
  const Timing fine60 = run(scene, 4, false);
  std::cout << "| run | vertices | s/step | ratio to r-ITR |\n| --- | --- | --- | --- |\n";
  for (const auto &[name, t] : {std::pair{"r-ITR", ritr}, {"fixed, same mesh", same}, {"fixed, refined twice", fine15},
                                {"fixed, refined three times", fine60}})
    std::cout << "| " << name << " | " << t.vertices << " | " << t.seconds_per_step << " | "
              << t.seconds_per_step / ritr.seconds_per_step << " |\n";
  std::cout << "r-ITR per step: " << ritr.outer_iterations << " outer iterations, " << ritr.inner_iterations
            << " inner Newton iterations; inner solves " << ritr.inner << " s, transfer " << ritr.transfer
            << " s, outer linear solves " << ritr.outer << " s of " << ritr.seconds_per_step << " s" << std::endl;
  EXPECT_GT(ritr.outer_iterations, 0.0);
}
