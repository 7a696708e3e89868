// Bad input: one clear line naming the file and entry, exit code 2, nothing already in the
// output directory overwritten. Non-convergence: exit code 3 with the written steps kept.
#include <gtest/gtest.h>

#include <filesystem>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  const char *valid_scene = R"(set dimension = 2
set time step = 0.01
set end time = 0.02
set output directory = OUTPUT
subsection Body 0
  set shape = rectangle
  set upper = 1, 0.2
  set subdivisions = 4, 1
  set translation = 0, 0.01
end
subsection Obstacle 0
  set type = plane
  set point = 0, 0
end
subsection Contact
  set dhat = 1e-3
end
)";

  std::string scene_with(const std::string &name, const std::string &extra, const std::string &replace = "",
                         const std::string &by = "")
  {
    std::string text = valid_scene;
    const std::string out = "output/errors/" + name;
    text.replace(text.find("OUTPUT"), 6, out);
    if (!replace.empty())
      text.replace(text.find(replace), replace.size(), by);
    text += extra;
    std::filesystem::create_directories(out);
    // A previous result that bad input must not touch.
    write_file(out + "/log.csv", "previous results\n");
    const std::string file = "output/errors/" + name + ".prm";
    write_file(file, text);
    return file;
  }

  void expect_input_error(const std::string &name, const std::string &extra, const std::string &expected_words,
                          const std::string &replace = "", const std::string &by = "")
  {
    const std::string file = scene_with(name, extra, replace, by);
    const RunResult   r    = run_ritr(file);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(file), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(expected_words), std::string::npos) << r.output;
    EXPECT_EQ(read_file("output/errors/" + name + "/log.csv"), "previous results\n");
  }
} // namespace

TEST(ErrorHandling, ValidSceneRuns)
{
  const RunResult r = run_ritr(scene_with("valid", ""));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(ErrorHandling, UnknownEntry) { expect_input_error("unknown", "set time stpe = 0.1\n", "time stpe"); }
TEST(ErrorHandling, MalformedValue) { expect_input_error("malformed", "", "time step", "set time step = 0.01", "set time step = fast"); }
TEST(ErrorHandling, MissingMeshFile)
{
  expect_input_error("missing_mesh", "", "nowhere.msh", "set shape = rectangle", "set shape = file\n  set file = nowhere.msh");
}
TEST(ErrorHandling, BadExpression)
{
  expect_input_error("expression", "subsection Body 0\n set initial velocity = 0; sin(\nend\n", "initial velocity");
}
TEST(ErrorHandling, InitialIntersection)
{
  expect_input_error("intersection", "", "intersects", "set translation = 0, 0.01", "set translation = 0, -0.05");
}
TEST(ErrorHandling, ContradictoryBoundaryConditions)
{
  expect_input_error("contradictory",
                     "subsection Dirichlet 0\n set enabled = true\n set region = 0.1 - x\n set displacement = 0; 0\nend\n"
                     "subsection Dirichlet 1\n set enabled = true\n set region = 0.1 - x\n set displacement = t; 0\nend\n",
                     "contradicts");
}
TEST(ErrorHandling, DegenerateElements)
{
  // A gmsh file whose only triangle has zero area.
  write_file("output/errors/flat.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 2 0 0\n"
                                       "$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n");
  expect_input_error("degenerate", "", "degenerate (zero-measure)", "set shape = rectangle",
                     "set shape = file\n  set file = flat.msh");
}
TEST(ErrorHandling, NonConvergenceKeepsWrittenSteps)
{
  const std::string file = scene_with("no_convergence", "subsection Solver\n set max iterations = 1\nend\n"
                                                        "subsection Body 0\n set initial velocity = 0; -3\nend\n");
  const RunResult r = run_ritr(file);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("did not converge"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists("output/errors/no_convergence/solution-00000.vtu"));
  EXPECT_TRUE(std::filesystem::exists("output/errors/no_convergence/summary.json"));
}
TEST(ErrorHandling, FoldedElements)
{
  // Three triangles around node 1; the last one overlaps the second (folded mesh).
  write_file("output/errors/folded.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n"
                                         "3 1 1 0\n4 0 1 0\n5 0.9 0.5 0\n$EndNodes\n$Elements\n3\n"
                                         "1 2 2 0 1 1 2 3\n2 2 2 0 1 1 3 4\n3 2 2 0 1 1 3 5\n$EndElements\n");
  expect_input_error("folded", "", "inverted (folded) elements", "set shape = rectangle",
                     "set shape = file\n  set file = folded.msh");
}
TEST(ErrorHandling, AdaptivityWithoutPhysicalAdmissibilityNeedsNoContact)
{
  expect_input_error("adaptivity_joint_contact",
                     "subsection Adaptivity\n set enabled = true\n set admissibility = geometric\nend\n",
                     "Adaptivity/admissibility");
}
