// Adaptivity/carry trust region on the reduced outer solve, one outer iteration per step, five
// dynamic steps of the free square whose optimal mesh is far from the uniform one
// (prm/verification/ritr/square_step_2d.prm):
//  - the first step is the same with and without it (both start at the initial radius);
//  - later steps move the nodes further with it than any step can without it, where every
//    step's region starts afresh;
//  - a run stopped after three steps and resumed to five ends where the uninterrupted run
//    ends, so the checkpoint carries the radius.
#include "run_ritr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace ritr::test_support;

namespace
{
  const std::string out = "ritr_carried_region_out";

  // Runs the square for `steps` steps with the region carried or not, in out/NAME.
  std::string run_square(const std::string &name, const bool carried, const int steps, const bool resume = false)
  {
    const std::string directory = out + "/" + name;
    std::string       scene     = read_file(source_dir() + "/prm/verification/ritr/square_step_2d.prm");
    scene = replaced(scene, "output/verification/ritr/square_step_2d", directory);
    scene += "set end time = " + std::to_string(0.01 * steps) + "\nset write nodal csv = true\n" +
             "subsection Adaptivity\n  set hessian = reduced\n  set max iterations = 1\n" +
             "  set carry trust region = " + (carried ? "true" : "false") + "\nend\n";
    const std::string prm = out + "/" + name + ".prm";
    std::filesystem::create_directories(out);
    write_file(prm, scene);
    const RunResult r = run_ritr(prm + (resume ? " --resume" : ""));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return directory;
  }

  std::string nodes(const std::string &directory, const int step)
  {
    char name[32];
    std::snprintf(name, sizeof(name), "/nodes-%05d.csv", step);
    return directory + name;
  }

  // The reference positions (u_x, u_y) of every node after `step`.
  std::vector<double> reference(const std::string &directory, const int step)
  {
    const auto x = csv_column(nodes(directory, step), "u_x"), y = csv_column(nodes(directory, step), "u_y");
    std::vector<double> u(x);
    u.insert(u.end(), y.begin(), y.end());
    return u;
  }

  double max_difference(const std::vector<double> &a, const std::vector<double> &b)
  {
    double d = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      d = std::max(d, std::abs(a[i] - b[i]));
    return d;
  }

  // The largest per-step node move |u^{n+1} - u^n|_inf over steps first..last.
  double largest_move(const std::string &directory, const int first, const int last)
  {
    double move = 0;
    for (int n = first; n <= last; ++n)
      move = std::max(move, max_difference(reference(directory, n), reference(directory, n - 1)));
    return move;
  }
} // namespace

TEST(RitrCarriedRegion, LetsTheNodesFollowFurtherAndResumes)
{
  std::filesystem::remove_all(out);
  const std::string fresh   = run_square("fresh", false, 5);
  const std::string carried = run_square("carried", true, 5);

  EXPECT_EQ(reference(carried, 1), reference(fresh, 1));
  const double fresh_move = largest_move(fresh, 1, 5), carried_move = largest_move(carried, 2, 5);
  std::printf("largest step move: fresh %.4f, carried %.4f\n", fresh_move, carried_move);
  EXPECT_GT(fresh_move, 0.0);
  EXPECT_GT(carried_move, 1.3 * fresh_move);

  // Three steps, then resumed to five in the same directory.
  run_square("resumed", true, 3);
  const std::string resumed = run_square("resumed", true, 5, true);
  EXPECT_LE(max_difference(reference(resumed, 5), reference(carried, 5)), 1e-12);
}
