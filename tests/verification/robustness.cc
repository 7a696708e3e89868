// Robustness scenes from prm/verification run to the end with every invariant holding:
// exit code 0, no violation in summary.json, and in every log.csv row a positive minimum
// distance and a positive minimum deformed Jacobian.
#include <algorithm>
#include <gtest/gtest.h>

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
    std::istringstream log(read_file(directory + "/log.csv"));
    std::string        line;
    std::getline(log, line);  // header: find the columns by name
    std::vector<std::string> header;
    {
      std::istringstream cells(line);
      std::string        cell;
      while (std::getline(cells, cell, ','))
        header.push_back(cell);
    }
    const auto column = [&](const std::string &name) {
      return std::find(header.begin(), header.end(), name) - header.begin();
    };
    const auto distance = column("min_distance"), jacobian = column("min_deformed_jacobian");
    ASSERT_LT(jacobian, static_cast<long>(header.size()));
    int rows = 0;
    while (std::getline(log, line))
      {
        std::vector<double> v;
        std::istringstream  cells(line);
        std::string         cell;
        while (std::getline(cells, cell, ','))
          v.push_back(std::stod(cell));
        ASSERT_EQ(v.size(), header.size());
        EXPECT_GT(v[distance], 0.0) << "step " << v[0] << ": bodies touch or intersect";
        EXPECT_GT(v[jacobian], 0.0) << "step " << v[0] << ": an element inverted";
        ++rows;
      }
    EXPECT_GT(rows, 0);
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
  EXPECT_NEAR(u[1], 0.141198, 1e-4);
  EXPECT_NEAR(u[2], 0.858802, 1e-4);
}

// A gmsh body falling into a gap between gmsh obstacle blocks (meshes/wedge.msh, funnel.msh).
TEST(Robustness, GmshWedgeDropThrough2D)
{
  run_scene_file(source_dir() + "/prm/wedge_drop_through.prm", "output/wedge_drop_through");
}
