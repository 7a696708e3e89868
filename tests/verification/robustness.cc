// Robustness scenes from prm/verification run to the end with every invariant holding:
// exit code 0, no violation in summary.json, and in every log.csv row a positive minimum
// distance and a positive minimum deformed Jacobian.
#include <algorithm>
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  void run_scene_file(const std::string &file, const std::string &directory)
  {
    const RunResult r = run_ritr(file);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(read_file(directory + "/summary.json").find("\"invariant_violations\": []"), std::string::npos);
    const CsvTable log      = read_csv(directory + "/log.csv");
    const auto     distance = log.column("min_distance"), jacobian = log.column("min_deformed_jacobian");
    ASSERT_LT(jacobian, log.header.size());
    for (const auto &v : log.rows)
      {
        ASSERT_EQ(v.size(), log.header.size());
        EXPECT_GT(v[distance], 0.0) << "step " << v[0] << ": bodies touch or intersect";
        EXPECT_GT(v[jacobian], 0.0) << "step " << v[0] << ": an element inverted";
      }
    EXPECT_GT(log.rows.size(), 0u);
  }

  void run_scene(const std::string &name)
  {
    run_scene_file(source_dir() + "/prm/verification/" + name + ".prm", "output/verification/" + name);
  }
} // namespace

TEST(Robustness, SoftBallOnSpikes2D) { run_scene("ball_on_spikes_2d"); }
TEST(Robustness, BarImpactAt80MetresPerSecond2D) { run_scene("bar_impact_2d"); }
TEST(Robustness, SoftBallOnSpikes3D) { run_scene("ball_on_spikes_3d"); }
TEST(Robustness, TwoBodiesCollide2D) { run_scene("two_bodies_2d"); }

// r-adaptivity on the paper's 1D rod: the scene runs, and after the first step the interior
// nodes sit at the optimum that ritr_optimality_1d finds by brute force (0.1412, 0.8588).
TEST(Robustness, AdaptiveRod1D)
{
  run_scene_file(source_dir() + "/prm/ritr_rod_1d.prm", "output/ritr_rod_1d");
  std::istringstream nodes(read_file("output/ritr_rod_1d/nodes-00001.csv"));
  std::string        line;
  std::getline(nodes, line);
  std::vector<double> u;
  while (std::getline(nodes, line))
    u.push_back(std::stod(line.substr(line.find(',') + 1)));
  std::sort(u.begin(), u.end());
  ASSERT_EQ(u.size(), 4u);
  // Every r-ITR step says why its outer iteration stopped, and summary.json counts them.
  const CsvTable log = read_csv("output/ritr_rod_1d/log.csv");
  const auto     stop = log.column("outer_stop");
  ASSERT_LT(stop, log.header.size());
  std::map<std::string, int> stops;
  for (const auto &row : log.text)
    ++stops[row[stop]];
  for (const auto &[name, count] : stops)
    EXPECT_TRUE(name == "converged" || name == "small_decrease" || name == "no_decrease" ||
                name == "iteration_limit") << name;
  const std::string summary = read_file("output/ritr_rod_1d/summary.json");
  EXPECT_NE(summary.find("\"outer_stops\": {\"converged\": " + std::to_string(stops["converged"]) +
                         ", \"small_decrease\": " + std::to_string(stops["small_decrease"])),
            std::string::npos) << summary;
  EXPECT_NEAR(u[1], 0.141198, 1e-4);
  EXPECT_NEAR(u[2], 0.858802, 1e-4);
}

// A gmsh body falling into a gap between gmsh obstacle blocks (meshes/wedge.msh, funnel.msh).
TEST(Robustness, GmshWedgeDropThrough2D)
{
  run_scene_file(source_dir() + "/prm/wedge_drop_through.prm", "output/wedge_drop_through");
}
