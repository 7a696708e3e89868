// Robustness scenes from prm/verification run to the end with every invariant holding:
// exit code 0, no violation in summary.json, and in every log.csv row a positive minimum
// distance and a positive minimum deformed Jacobian.
#include <gtest/gtest.h>

#include <sstream>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  void run_scene(const std::string &name)
  {
    const RunResult r = run_ritr(source_dir() + "/prm/verification/" + name + ".prm");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string directory = "output/verification/" + name;
    EXPECT_NE(read_file(directory + "/summary.json").find("\"invariant_violations\": []"), std::string::npos);
    std::istringstream log(read_file(directory + "/log.csv"));
    std::string        line;
    std::getline(log, line);  // header
    int rows = 0;
    while (std::getline(log, line))
      {
        std::vector<double> v;
        std::istringstream  cells(line);
        std::string         cell;
        while (std::getline(cells, cell, ','))
          v.push_back(std::stod(cell));
        ASSERT_EQ(v.size(), 10u);
        EXPECT_GT(v[6], 0.0) << "step " << v[0] << ": bodies touch or intersect";
        EXPECT_GT(v[8], 0.0) << "step " << v[0] << ": an element inverted";
        ++rows;
      }
    EXPECT_GT(rows, 0);
  }
} // namespace

TEST(Robustness, SoftBallOnSpikes2D) { run_scene("ball_on_spikes_2d"); }
TEST(Robustness, BarImpactAt80MetresPerSecond2D) { run_scene("bar_impact_2d"); }
TEST(Robustness, SoftBallOnSpikes3D) { run_scene("ball_on_spikes_3d"); }
TEST(Robustness, TwoBodiesCollide2D) { run_scene("two_bodies_2d"); }
