// Bad input: one clear line naming the file and entry, exit code 2, nothing already in the
// output directory overwritten. Non-convergence: exit code 3 with the written steps kept.
// The corpus at the end holds the hostile inputs: each one runs the ritr executable.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  std::string scene_with(const std::string &name, const std::string &extra, const std::string &replace = "",
                         const std::string &by = "")
  {
    const std::string out  = "output/errors/" + name;
    std::string       text = replaced(small_scene, "OUTPUT", out);
    if (!replace.empty())
      text = replaced(text, replace, by);
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

TEST(ErrorHandling, EveryNodePrescribedRuns)
{
  // No free unknown is left: the Newton system is empty, which is no error.
  const RunResult r = run_ritr(scene_with("all_prescribed", "subsection Dirichlet 0\n set enabled = true\n"
                                                            " set region = 1\n set displacement = 0; 0.1 * t\nend\n"));
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
// A run owns its directory: the previous run's outputs and stale temporaries go, other
// files stay, and the summary says whether the run completed.
TEST(ErrorHandling, RunReplacesThePreviousRun)
{
  const std::string file = scene_with("previous_run", ""), out = "output/errors/previous_run/";
  write_file(out + "summary.json", "{\n  \"complete\": true,\n  \"steps\": 30\n}\n");
  write_file(out + "log.csv", "step\n" + std::string(30, '\n'));
  for (const char *old : {"solution-00030.vtu", "reference-00029.vtu", "nodes-00030.csv", "log.csv.tmp",
                          "solution-00031.vtu.tmp", "notes.txt"})
    write_file(out + old, "previous run\n");
  const RunResult r = run_ritr(file);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char *old : {"solution-00030.vtu", "reference-00029.vtu", "nodes-00030.csv", "log.csv.tmp",
                          "solution-00031.vtu.tmp"})
    EXPECT_FALSE(std::filesystem::exists(out + old)) << old;
  EXPECT_TRUE(std::filesystem::exists(out + "notes.txt"));  // not an output of ritr
  const std::string summary = read_file(out + "summary.json");
  EXPECT_NE(summary.find("\"complete\": true"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"steps\": 2"), std::string::npos) << summary;
  const std::string log = read_file(out + "log.csv");
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 3) << log;
}
TEST(ErrorHandling, FailedRunIsNotComplete)
{
  const std::string file = scene_with("failed_run", "subsection Solver\n set max iterations = 1\nend\n"
                                                    "subsection Body 0\n set initial velocity = 0; -3\nend\n");
  const std::string out  = "output/errors/failed_run/";
  write_file(out + "summary.json", "{\n  \"complete\": true,\n  \"steps\": 30\n}\n");
  write_file(out + "log.csv", "step\n" + std::string(30, '\n'));
  write_file(out + "solution-00030.vtu", "previous run\n");
  const RunResult r = run_ritr(file);
  ASSERT_EQ(r.exit_code, 3) << r.output;
  const std::string summary = read_file(out + "summary.json");
  EXPECT_NE(summary.find("\"complete\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"failure\": \"step 1"), std::string::npos) << summary;
  const std::string log = read_file(out + "log.csv");
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;  // the header: step 1 failed
  EXPECT_FALSE(std::filesystem::exists(out + "solution-00030.vtu"));
  EXPECT_TRUE(std::filesystem::exists(out + "solution-00000.vtu"));
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
// An expression that is finite where the scene is checked (t = 0 and the first step) but not
// at a later step's time stops the run as bad input that names the expression and the time,
// and keeps the steps written before it.
TEST(ErrorHandling, ExpressionNotFiniteAtALaterStep)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    {"Obstacle 0/translation", "subsection Obstacle 0\n set translation = 0; log(0.015 - t)\nend\n"},
    {"Gravity/load factor", "subsection Gravity\n set load factor = 1 + sqrt(0.015 - t)\nend\n"},
    {"Dirichlet 0/displacement", "subsection Dirichlet 0\n set enabled = true\n set region = 0.1 - x\n"
                                 " set displacement = 0; 0.01 * sqrt(0.015 - t)\nend\n"}};
  for (std::size_t c = 0; c < cases.size(); ++c)
    {
      const auto &[entry, extra] = cases[c];
      const std::string name = "later_" + std::to_string(c), out = "output/errors/" + name;
      std::filesystem::remove_all(out);
      const std::string file = scene_with(name, extra);
      const RunResult   r    = run_ritr(file, "2>&1 >/dev/null");
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_NE(r.output.find(entry + ": is not finite at x = ("), std::string::npos) << r.output;
      EXPECT_NE(r.output.find("t = 0.02; steps written so far are kept"), std::string::npos) << r.output;
      EXPECT_TRUE(std::filesystem::exists(out + "/solution-00001.vtu")) << entry;
      const std::string summary = read_file(out + "/summary.json");
      EXPECT_NE(summary.find("\"complete\": false"), std::string::npos) << summary;
      EXPECT_NE(summary.find("\"failure\": \"" + file), std::string::npos) << summary;
    }
}

// Output directories that pass for creatable but cannot be made: refused before anything is
// printed, the path and its parent untouched.
TEST(ErrorHandling, OutputDirectoryThatCannotBeCreated)
{
  const std::string folder = "output/errors/uncreatable";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::filesystem::create_symlink("missing/target", folder + "/dangling");
  for (const std::string &directory : {std::string("/proc/ritr-output"), folder + "/dangling", folder + "/dangling/below"})
    {
      const std::string scene = folder + "/scene.prm";
      write_file(scene, replaced(small_scene, "OUTPUT", directory));
      const auto      before = snapshot(folder);
      const RunResult r      = run_ritr(scene, "2>&1 >" + folder + ".stdout");
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_EQ(read_file(folder + ".stdout"), "") << directory;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_EQ(r.output.rfind("ritr: error: " + scene + ":4: output directory: '" + directory + "' cannot be created", 0), 0u)
        << r.output;
      EXPECT_TRUE(snapshot(folder) == before) << directory;
      EXPECT_FALSE(std::filesystem::exists(directory)) << directory;
    }
}

// A command line that is not one of the usages: one line saying what is wrong and how to call
// ritr, exit code 2.
TEST(ErrorHandling, CommandLineMisuse)
{
  for (const std::string arguments : {"", "a.prm b.prm", "--frobnicate", "a.prm --frobnicate", "--help --resume",
                                      "--resume", "--print-parameters a.prm"})
    {
      const RunResult r = run_ritr(arguments);
      EXPECT_EQ(r.exit_code, 2) << arguments << ": " << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << arguments << ": " << r.output;
      EXPECT_EQ(r.output.rfind("ritr: error: ", 0), 0u) << r.output;
      EXPECT_NE(r.output.find("(usage: ritr SCENE.prm [--resume] | ritr --print-parameters | ritr --help)\n"),
                std::string::npos)
        << r.output;
    }
  EXPECT_NE(run_ritr("a.prm --frobnicate").output.find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_EQ(run_ritr("--help").exit_code, 0);
}

TEST(ErrorHandling, AdaptivityWithoutPhysicalAdmissibilityNeedsNoContact)
{
  expect_input_error("adaptivity_joint_contact",
                     "subsection Adaptivity\n set enabled = true\n set admissibility = geometric\nend\n",
                     "Adaptivity/admissibility");
}

namespace
{
  // One bad input: a scene (by default the valid one, edited) and files written beside it, in
  // a folder of its own that also holds a previous run in `out/`.
  struct BadInput
  {
    std::string name;
    std::string expected;  // words the message must hold: the entry, or what is wrong
    std::string scene;     // "OUTPUT" stands for the output directory of the previous run
    std::vector<std::pair<std::string, std::string>> files;  // relative to the folder; "/" ends a folder
    std::string scene_name = "scene.prm";

    BadInput with(const std::string &path, const std::string &content = "/") const
    {
      BadInput c = *this;
      c.files.emplace_back(path, content);
      return c;
    }
  };

  BadInput appended(const std::string &name, const std::string &expected, const std::string &extra)
  {
    return {name, expected, small_scene + extra, {}};
  }
  BadInput edited(const std::string &name, const std::string &expected, const std::string &replace,
                  const std::string &by)
  {
    return {name, expected, replaced(small_scene, replace, by), {}};
  }
  BadInput whole(const std::string &name, const std::string &expected, const std::string &text)
  {
    return {name, expected, text, {}};
  }
  std::string repeated(const std::string &s, const unsigned int n)
  {
    std::string r;
    for (unsigned int i = 0; i < n; ++i)
      r += s;
    return r;
  }
  std::string body(const std::string &lines) { return "subsection Body 0\n" + lines + "\nend\n"; }
  std::string with_friction(const std::string &lines) { return "subsection Contact\n" + lines + "\nend\n"; }
  std::string dirichlet(const std::string &lines)
  {
    return "subsection Dirichlet 0\n set enabled = true\n" + lines + "\nend\n";
  }
  std::string obstacle(const std::string &lines) { return "subsection Obstacle 0\n" + lines + "\nend\n"; }

  const std::string triangle_nodes = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n";
  const std::string triangle_cells = "$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n";

  // A second body or obstacle of the small scene (whose strip spans [0, 1] x [0.01, 0.21]).
  std::string second_body(const std::string &lines)
  {
    return "subsection Body 1\n set enabled = true\n" + lines + "\nend\n";
  }
  std::string second_obstacle(const std::string &lines) { return "subsection Obstacle 1\n" + lines + "\nend\n"; }

  // A gmsh 2.2 file of `nodes` ("tag x y z" lines) and `elements` ("tag type 2 0 1 nodes..." lines).
  std::string gmsh(const std::vector<std::string> &nodes, const std::vector<std::string> &elements)
  {
    std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
    for (const auto &n : nodes)
      text += n + "\n";
    text += "$EndNodes\n$Elements\n" + std::to_string(elements.size()) + "\n";
    for (const auto &e : elements)
      text += e + "\n";
    return text + "$EndElements\n";
  }

  // A rod read from rod.msh above a wall at x = -1.
  const std::string rod_scene = "set dimension = 1\nset time step = 0.01\nset end time = 0.02\n"
                                "set output directory = OUTPUT\n"
                                "subsection Body 0\n set shape = file\n set file = rod.msh\nend\n"
                                "subsection Obstacle 0\n set type = plane\n set point = -1\n set normal = 1\nend\n";

  // A 3D block above the obstacle surface shape.obj.
  const std::string obj_scene = "set dimension = 3\nset time step = 0.01\nset end time = 0.02\n"
                                "set output directory = OUTPUT\n"
                                "subsection Body 0\n set shape = box\n set upper = 1, 0.2, 1\n"
                                " set translation = 0, 0.5, 0\nend\n"
                                "subsection Obstacle 0\n set type = file\n set file = shape.obj\nend\n";
  // The 2D strip above the obstacle polyline shape.obj.
  const std::string obj_scene_2d =
    replaced(small_scene, "set type = plane\n  set point = 0, 0", "set type = file\n  set file = shape.obj");
  const std::string a_triangle = "v 0 0 0\nv 1 0 0\nv 0 0 1\n";

  // A 3D scene: a ball of radius 0.5 at (0, 0.8, 0), without obstacles.
  const std::string ball_scene = "set dimension = 3\nset time step = 0.01\nset end time = 0.02\n"
                                 "set output directory = OUTPUT\n"
                                 "subsection Body 0\n set shape = ball\n set center = 0, 0.8, 0\n set radius = 0.5\n"
                                 " set shape refinements = 0\nend\n";

  std::vector<BadInput> bad_inputs()
  {
    const std::string file_body = "set shape = rectangle";
    return {
      // Lines of any length are parsed without recursion, and echoed shortened.
      edited("long_value", "time step", "set time step = 0.01", "set time step = " + repeated("x", 30000)),
      appended("long_entry_name", "No entry with name", "set " + repeated("e", 30000) + " = 1\n"),
      appended("long_subsection", "no such subsection", "subsection " + repeated("B", 30000) + "\nend\n"),
      appended("long_junk", "could not be parsed", repeated("junk ", 10000) + "\n"),
      appended("long_expression", "Body 0/initial velocity", body(" set initial velocity = 0; " + repeated("(", 30000))),
      edited("long_mesh_file", "Body 0/file", file_body, "set shape = file\n set file = " + repeated("m", 30000)),
      // A scene must set something; a folder is not a scene.
      whole("empty_file", "sets no entry", ""),
      whole("only_comments", "sets no entry", "# nothing\n\n  # here\nsubsection Body 0\nend\n"),
      BadInput{"folder_as_scene", "is a directory", "", {{"folder/", "/"}}, "folder"},
      whole("binary_file", "could not be parsed", std::string("\x7f" "ELF\x02\x01\x01\0\0\0\xff\xfe\x1b[2J\n", 17)),
      // The output directory is bad input too: checked before anything is written.
      edited("output_is_a_file", "output directory", "OUTPUT", "OUTPUT/log.csv"),
      edited("output_empty", "output directory", "set output directory = OUTPUT", "set output directory ="),
      edited("output_under_a_file", "output directory", "OUTPUT", "OUTPUT/log.csv/new"),
      appended("output_temporary_is_a_folder", "summary.json.tmp", "").with("out/summary.json.tmp/"),
      appended("output_output_is_a_folder", "solution-00001.vtu", "").with("out/solution-00001.vtu/"),
      edited("output_path_too_long", "output directory", "OUTPUT", "OUTPUT/" + repeated("d", 100000)),
      // Lists need exactly dim numbers.
      appended("acceleration_short", "Gravity/acceleration", "subsection Gravity\n set acceleration = -9.81\nend\n"),
      edited("translation_short", "Body 0/translation", "set translation = 0, 0.01", "set translation = 0.1"),
      appended("center_short", "Body 0/center", body(" set center = 0")),
      edited("upper_long", "Body 0/upper", "set upper = 1, 0.2", "set upper = 1, 0.2, 0.3"),
      edited("subdivisions_short", "Body 0/subdivisions", "set subdivisions = 4, 1", "set subdivisions = 4"),
      edited("point_short", "Obstacle 0/point", "set point = 0, 0", "set point = 0"),
      appended("normal_empty", "Obstacle 0/normal", obstacle(" set normal =")),
      appended("short_list_in_body_3", "Body 3/translation",
               "subsection Body 3\n set enabled = true\n set translation = 1\nend\n"),
      // Expressions are evaluated before the run: NaN and inf name their entry.
      appended("velocity_nan", "Body 0/initial velocity", body(" set initial velocity = 0; sqrt(-1)")),
      appended("velocity_inf", "Body 0/initial velocity", body(" set initial velocity = 0; 1/0")),
      appended("load_factor_nan", "Gravity/load factor", "subsection Gravity\n set load factor = sqrt(-1)\nend\n"),
      appended("displacement_inf_at_first_step", "Dirichlet 0/displacement",
               dirichlet(" set region = 0.1 - x\n set displacement = 0; 1/(t - 0.01)")),
      appended("region_nan", "Dirichlet 0/region", dirichlet(" set region = sqrt(x - 2)")),
      appended("obstacle_translation_nan", "Obstacle 0/translation", obstacle(" set translation = 0; log(t - 1)")),
      appended("rotation_angle_inf", "Obstacle 0/rotation angle", obstacle(" set rotation angle = 1/t")),
      // Step counts: whole, finite, landing on the end time.
      edited("time_step_tiny", "time step", "set time step = 0.01", "set time step = 1e-300"),
      edited("time_step_above_end_time", "time step", "set time step = 0.01", "set time step = 1"),
      edited("end_time_not_whole", "end time", "set time step = 0.01", "set time step = 0.015"),
      edited("time_step_zero", "time step", "set time step = 0.01", "set time step = 0"),
      appended("friction_without_epsilon_v", "Contact/epsilon v",
               with_friction(" set friction coefficient = 0.3\n set epsilon v = 0")),
      appended("barrier_stiffness_inf", "Contact/barrier stiffness", with_friction(" set barrier stiffness = inf")),
      appended("barrier_stiffness_suffix", "Contact/barrier stiffness", with_friction(" set barrier stiffness = 1e5abc")),
      edited("duplicate_node", "defines node 2 twice", file_body, "set shape = file\n set file = twice.msh")
        .with("twice.msh", triangle_nodes + "2 0 1 0\n3 0 1 0\n" + triangle_cells),
      // Bytes that would cut or garble the line are escaped.
      edited("nul_in_value", "end time", "set end time = 0.02", std::string("set end time = 0.0\0" "2", 20)),
      appended("nul_in_expression", "Body 0/initial velocity", body(std::string(" set initial velocity = 0; 1\0x", 31))),
      appended("control_bytes", "Body 0/initial velocity", body(" set initial velocity = 0; \x1b[31m\x07")),
      appended("no_such_subsection", "scene.prm:18: There is no such subsection to be entered: Bodyy 0",
               "subsection Bodyy 0\nend\n"),
      // Kinds that held before.
      appended("unknown_entry", "time stpe", "set time stpe = 0.1\n"),
      edited("malformed_value", "time step", "set time step = 0.01", "set time step = fast"),
      appended("bad_selection", "mode", "set mode = dynamc\n"),
      appended("bad_bool", "write nodal csv", "set write nodal csv = maybe\n"),
      appended("dimension_4", "dimension", "set dimension = 4\n"),
      appended("set_without_value", "Invalid format of 'set'", "set time step 0.1\n"),
      appended("end_without_subsection", "no subsection to leave", "end\n"),
      appended("subsection_without_end", "unequal numbers of 'subsection' and 'end'", "subsection Contact\n"),
      edited("missing_mesh", "Body 0/file", file_body, "set shape = file\n set file = nowhere.msh"),
      appended("expression_syntax", "Body 0/initial velocity", body(" set initial velocity = 0; sin(")),
      appended("expression_components", "Body 0/initial velocity", body(" set initial velocity = 0")),
      edited("initial_intersection", "intersects", "set translation = 0, 0.01", "set translation = 0, -0.05"),
      appended("no_body", "the scene has no body", body(" set enabled = false")),
      appended("poisson_ratio_half", "Material 0", "subsection Material 0\n set poisson ratio = 0.5\nend\n"),
      appended("dhat_zero", "Contact/dhat", with_friction(" set dhat = 0")),
      appended("dirichlet_ids_and_region", "Dirichlet 0", dirichlet(" set region = x\n set boundary ids = 1")),
      appended("dirichlet_selects_nothing", "selects no node", dirichlet(" set region = -1")),
      // A sliding node prescribes the material point it moves to: only a uniform displacement
      // means the same condition for all of them, and only the trust-region solve folds it in.
      appended("sliding_dirichlet_not_uniform", "Dirichlet 0/sliding reference nodes",
               dirichlet(" set region = 0.1 - x\n set displacement = 0; 0.1 * y * t\n set sliding reference nodes = true") +
                 "subsection Adaptivity\n set enabled = true\nend\n"),
      appended("sliding_dirichlet_line_search", "Dirichlet 0/sliding reference nodes",
               dirichlet(" set region = 0.1 - x\n set sliding reference nodes = true") +
                 "subsection Adaptivity\n set enabled = true\n set hessian = truncated\nend\n"),
      appended("shape_of_another_dimension", "Body 0: shape 'box'", body(" set shape = box")),
      appended("disk_radius_zero", "Body 0: radius", body(" set shape = disk\n set radius = 0")),
      appended("folded_mesh_in_body_2", "Body 2: the mesh has inverted",
               "subsection Body 2\n set enabled = true\n set shape = file\n set file = folded.msh\nend\n")
        .with("folded.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 1 1 0\n"
                            "4 0 1 0\n5 0.9 0.5 0\n$EndNodes\n$Elements\n3\n1 2 2 0 1 1 2 3\n2 2 2 0 1 1 3 4\n"
                            "3 2 2 0 1 1 3 5\n$EndElements\n"),
      // The initial state is free of intersections: nothing inside a body or a closed obstacle,
      // found by inside tests since no boundary crosses; each named.
      appended("obstacle_inside_body", "the initial configuration intersects: Obstacle 1 lies inside Body 0",
               second_obstacle(" set type = box\n set point = 0.5, 0.1\n set size = 0.05, 0.05")),
      appended("body_inside_body", "the initial configuration intersects: Body 1 lies inside Body 0",
               second_body(" set lower = 0.4, 0.05\n set upper = 0.6, 0.15")),
      appended("spikes_inside_body", "the initial configuration intersects: Obstacle 1 lies inside Body 0",
               second_obstacle(" set type = spikes\n set point = 0.5, 0.05\n set size = 0.2\n set count = 3\n"
                               " set spike height = 0.05")),
      appended("body_inside_closed_obstacle", "the initial configuration intersects: Body 1 lies inside Obstacle 1",
               second_obstacle(" set type = box\n set point = 3, 0.5\n set size = 1, 1") +
                 second_body(" set lower = 2.9, 0.4\n set upper = 3.1, 0.6")),
      whole("obstacle_inside_ball", "the initial configuration intersects: Obstacle 0 lies inside Body 0",
            ball_scene + "subsection Obstacle 0\n set type = box\n set point = 0, 0.8, 0\n set size = 0.1, 0.1, 0.1\nend\n"),
      whole("ball_inside_ball", "the initial configuration intersects: Body 1 lies inside Body 0",
            ball_scene + "subsection Body 1\n set enabled = true\n set shape = ball\n set center = 0.05, 0.8, 0\n"
                         " set radius = 0.1\n set shape refinements = 0\nend\n"),
      edited("crossing_named", "the initial configuration intersects: Body 0 and Obstacle 0 overlap or touch",
             "set translation = 0, 0.01", "set translation = 0, -0.05"),
      // 1D meshes get the mesh checks of 2D and 3D.
      whole("rod_duplicated_segment", "rod.msh' has a duplicated segment: element 3 repeats the nodes of element 2",
            rod_scene)
        .with("rod.msh", gmsh({"1 0 0 0", "2 0.5 0 0", "3 1 0 0"}, {"1 1 2 0 1 1 2", "2 1 2 0 1 2 3", "3 1 2 0 1 3 2"})),
      whole("rod_folded", "Body 0: the mesh has inverted (folded) elements", rod_scene)
        .with("rod.msh", gmsh({"1 0 0 0", "2 1 0 0", "3 0.5 0 0"}, {"1 1 2 0 1 1 2", "2 1 2 0 1 2 3"})),
      edited("triangle_duplicated", "has a duplicated triangle: element 3 repeats the nodes of element 1", file_body,
             "set shape = file\n set file = twice.msh")
        .with("twice.msh", gmsh({"1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0"},
                                {"1 2 2 0 1 1 2 3", "2 2 2 0 1 1 3 4", "3 2 2 0 1 3 1 2"})),
      whole("tetrahedron_duplicated", "has a duplicated tetrahedron: element 2 repeats the nodes of element 1",
            replaced(ball_scene, " set shape = ball", " set shape = file\n set file = twice.msh"))
        .with("twice.msh", gmsh({"1 0 0 0", "2 1 0 0", "3 0 1 0", "4 0 0 1"}, {"1 4 2 0 1 1 2 3 4", "2 4 2 0 1 4 3 2 1"})),
      // .obj obstacles: every coordinate a finite number, every index a vertex, every element
      // with a length or area; the file and line named.
      whole("obj_missing_coordinate", "shape.obj:2: a vertex needs 3 coordinates, this one has 2", obj_scene)
        .with("shape.obj", "v 0 0 0\nv 1 0\nv 0 0 1\nf 1 2 3\n"),
      whole("obj_nan_coordinate", "shape.obj:2: vertex coordinate 'nan' is not a finite number", obj_scene)
        .with("shape.obj", "v 0 0 0\nv 1 0 nan\nv 0 0 1\nf 1 2 3\n"),
      whole("obj_word_coordinate", "shape.obj:3: vertex coordinate 'abc' is not a number", obj_scene)
        .with("shape.obj", "v 0 0 0\nv 1 0 0\nv 0 0 abc\nf 1 2 3\n"),
      whole("obj_huge_coordinate", "shape.obj:1: vertex coordinate '1e400' is not a finite number", obj_scene)
        .with("shape.obj", "v 1e400 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"),
      whole("obj_zero_area", "shape.obj:4: a triangle of zero area", obj_scene)
        .with("shape.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"),
      whole("obj_repeated_index", "shape.obj:4: a triangle of zero area", obj_scene).with("shape.obj", a_triangle + "f 1 1 2\n"),
      whole("obj_index_not_a_number", "shape.obj:4: vertex index 'x' is not an integer", obj_scene)
        .with("shape.obj", a_triangle + "f 1 2 x\n"),
      whole("obj_index_out_of_range", "shape.obj:4: vertex index '7' names no vertex", obj_scene)
        .with("shape.obj", a_triangle + "f 1 2 7\n"),
      whole("obj_quad", "shape.obj:5: a face needs 3 vertices", obj_scene)
        .with("shape.obj", a_triangle + "v 1 0 1\nf 1 2 4 3\n"),
      BadInput{"obj_zero_segment", "shape.obj:3: a segment of zero length", obj_scene_2d,
               {{"shape.obj", "v -1 0\nv -1 0\nl 1 2\n"}}},
      BadInput{"msh_obstacle_zero_segment", "shape.msh' has a segment of zero length (segment 2)",
               replaced(obj_scene_2d, "shape.obj", "shape.msh"),
               {{"shape.msh", gmsh({"1 -1 0 0", "2 2 0 0", "3 2 0 0"}, {"1 1 2 0 1 1 2", "2 1 2 0 1 2 3"})}}},
      BadInput{"msh_obstacle_repeated_node", "shape.msh' has a segment of zero length (segment 2)",
               replaced(obj_scene_2d, "shape.obj", "shape.msh"),
               {{"shape.msh", gmsh({"1 -1 0 0", "2 2 0 0"}, {"1 1 2 0 1 1 2", "2 1 2 0 1 2 2"})}}},
      // Obstacle motions that define nothing.
      appended("plane_normal_zero", "scene.prm:19: Obstacle 0/normal: must be a nonzero direction", obstacle(" set normal = 0, 0")),
      whole("rotation_axis_zero", "Obstacle 0/rotation axis: must be a nonzero direction",
            replaced(obj_scene, "set file = shape.obj", "set type = plane\n set rotation axis = 0, 0, 0\n"
                                                        " set rotation angle = t")),
      // Sizes that cannot fit in memory are refused up front, with the numbers.
      whole("refinements_bomb", "Body 0: 20 x 20 x 20 subdivisions and 8 refinements make 6.7e+11 cells, which need",
            replaced(ball_scene, " set shape = ball", " set shape = box\n set subdivisions = 20, 20, 20\n set refinements = 8")),
      edited("subdivisions_bomb", "Body 0: 100000000 x 100000000 subdivisions and 0 refinements make 2e+16 cells",
             "set subdivisions = 4, 1", "set subdivisions = 100000000, 100000000"),
      whole("shape_refinements_bomb", "Body 0: 8 shape refinements and 8 refinements make",
            replaced(ball_scene, "set shape refinements = 0", "set shape refinements = 8\n set refinements = 8")),
      appended("spike_count_bomb", "Obstacle 0/count: 2000000000 spikes make 4e+09 segments, which need at least",
               obstacle(" set type = spikes\n set count = 2000000000")),
      // Numbers a pattern lets through but a double cannot hold, with their line.
      appended("epsilon_r_denormal", "scene.prm:19: Adaptivity/epsilon r",
               "subsection Adaptivity\n set epsilon r = 4.9e-324\nend\n"),
      // Coordinates a double cannot compute with.
      edited("coordinates_near_1e300", "Body 0: has a coordinate of 1e+300; coordinates must stay below",
             "set translation = 0, 0.01", "set translation = 1e300, 0.01"),
      // deal.II skips the pattern of a value with '{' (its parameter loops).
      appended("brace_in_selection", "mode: '{' is not allowed", "set mode = {static|dynamic}\n"),
      appended("brace_in_integer", "Body 0/material id: '{'", body(" set material id = {")),
    };
  }

  // GoogleTest names a case by its name rather than its bytes.
  void PrintTo(const BadInput &c, std::ostream *out) { *out << c.name; }

  class BadInputCorpus : public ::testing::TestWithParam<BadInput>
  {};

  // Exit code 2, nothing on standard output, one printable line on standard error naming the
  // scene file and the entry, and the case's folder (with the previous run) byte for byte
  // as before.
  TEST_P(BadInputCorpus, OneLineAndNothingTouched)
  {
    const BadInput   &c      = GetParam();
    const std::string folder = "output/bad_inputs/" + c.name, output = folder + "/out";
    const auto        expand = [&](std::string text) {
      for (auto at = text.find("OUTPUT"); at != std::string::npos; at = text.find("OUTPUT", at + 1))
        text.replace(at, 6, output);
      return text;
    };
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(output);
    for (const char *previous : {"log.csv", "summary.json", "solution.pvd", "solution-00000.vtu"})
      write_file(output + "/" + previous, std::string("previous run's ") + previous + "\n");
    for (const auto &[path, content] : c.files)
      if (path.back() == '/')
        std::filesystem::create_directories(folder + "/" + path);
      else
        write_file(folder + "/" + path, content);
    const std::string scene = folder + "/" + c.scene_name;
    if (!std::filesystem::is_directory(scene))
      write_file(scene, expand(c.scene));
    const auto before = snapshot(folder);

    const RunResult r = run_ritr(scene, "2>&1 >" + folder + ".stdout");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(read_file(folder + ".stdout"), "");
    ASSERT_FALSE(r.output.empty());
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
    EXPECT_EQ(r.output.rfind("ritr: error: " + scene, 0), 0u) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_LT(r.output.size(), 600u) << r.output;
    for (std::size_t i = 0; i + 1 < r.output.size(); ++i)
      EXPECT_GE(static_cast<unsigned char>(r.output[i]), 0x20) << "control byte at " << i << ": " << r.output;
    EXPECT_TRUE(snapshot(folder) == before) << "the scene's folder changed";
  }

  INSTANTIATE_TEST_SUITE_P(ErrorHandling, BadInputCorpus, ::testing::ValuesIn(bad_inputs()),
                           [](const auto &info) { return info.param.name; });
} // namespace
