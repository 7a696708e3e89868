// Scale: a 2D scene of about 100K vertices and a 3D scene of about 50K vertices run several
// steps; time per step and peak memory per vertex from their summary.json.
#include <gtest/gtest.h>

#include <regex>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  double json_number(const std::string &json, const std::string &key)
  {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(json, m, std::regex("\"" + key + "\": ([0-9.eE+-]+)"))) << key;
    return std::stod(m[1]);
  }

  void run_scale(const std::string &name)
  {
    const RunResult r = run_ritr(source_dir() + "/prm/benchmark/" + name + ".prm");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string json     = read_file("output/benchmark/" + name + "/summary.json");
    const double      vertices = json_number(json, "n_vertices");
    std::cout << "| " << name << " | " << vertices << " | " << json_number(json, "n_cells") << " | "
              << json_number(json, "wall_seconds_per_step") << " | "
              << json_number(json, "total_newton_iterations") / json_number(json, "steps") << " | "
              << json_number(json, "peak_rss_bytes") / vertices / 1024 << " |" << std::endl;
    EXPECT_NE(json.find("\"invariant_violations\": []"), std::string::npos);
  }
} // namespace

TEST(Scale, TwoDimensionsHundredThousandVertices) { run_scale("scale_2d"); }
TEST(Scale, ThreeDimensionsFiftyThousandVertices) { run_scale("scale_3d"); }
