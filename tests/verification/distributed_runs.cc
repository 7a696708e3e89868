// mpirun -np 2 ritr SCENE.prm: a fixed-mesh run shared between two processes (Trilinos) ends
// where the serial run (CHOLMOD) ends -- the final positions within the Newton tolerance, the
// Newton iterations within 10 % -- in 2D and 3D, with contact and friction, for both
// distributed solvers; it writes the files of a serial run, once; r-adaptivity and the
// Newton variants that need the whole matrix are refused with one line and exit code 2; a
// shared run resumes on two processes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "run_ritr.h"

using namespace ritr::test_support;
namespace fs = std::filesystem;

namespace
{
  RunResult run_on_two_processes(const std::string &scene)
  {
    // Open MPI refuses to start as root unless told that it is meant (containers, CI).
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    // A process left waiting for the other in a collective call would hang the test: two
    // minutes are ten times what these runs take.
    return run_command("timeout 120 mpirun --oversubscribe -np 2 " + ritr_binary() + " " + scene);
  }

  // `text` with the value of its first `set NAME = ...` replaced.
  std::string with_entry(const std::string &text, const std::string &name, const std::string &value)
  {
    const std::regex entry("set " + name + " *=[^\n]*");
    EXPECT_TRUE(std::regex_search(text, entry)) << name;
    return std::regex_replace(text, entry, "set " + name + " = " + value, std::regex_constants::format_first_only);
  }

  double json_number(const std::string &json, const std::string &key)
  {
    const std::size_t at = json.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return at == std::string::npos ? std::nan("") : std::atof(json.c_str() + at + key.size() + 4);
  }

  // The last frame's nodal CSV of a run.
  CsvTable last_nodes(const std::string &folder)
  {
    std::string last;
    for (const auto &entry : fs::directory_iterator(folder))
      if (const std::string name = entry.path().filename().string(); name.rfind("nodes-", 0) == 0 && name > last)
        last = name;
    return read_csv(folder + "/" + last);
  }

  std::vector<std::string> file_names(const std::string &folder)
  {
    std::vector<std::string> names;
    for (const auto &entry : fs::directory_iterator(folder))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  // Runs `scene` (a template with OUTPUT for its output directory) serially and on two
  // processes and compares the two.
  void expect_shared_run_matches_serial(const std::string &name, const std::string &scene, const double tolerance)
  {
    const std::string serial = "output/distributed_runs/" + name + "-serial",
                      shared = "output/distributed_runs/" + name + "-shared";
    fs::remove_all(serial);
    fs::remove_all(shared);
    write_file(name + "-serial.prm", replaced(scene, "OUTPUT", serial));
    write_file(name + "-shared.prm", replaced(scene, "OUTPUT", shared));
    const RunResult one = run_ritr(name + "-serial.prm");
    ASSERT_EQ(one.exit_code, 0) << one.output;
    const RunResult two = run_on_two_processes(name + "-shared.prm");
    ASSERT_EQ(two.exit_code, 0) << two.output;
    EXPECT_NE(two.output.find("on 2 processes"), std::string::npos) << two.output;
    // Progress is printed once, by the writer.
    EXPECT_EQ(std::count(two.output.begin(), two.output.end(), '\n'),
              std::count(one.output.begin(), one.output.end(), '\n')) << two.output;

    const std::string summary_one = read_file(serial + "/summary.json"),
                      summary_two = read_file(shared + "/summary.json");
    EXPECT_NE(summary_two.find("\"complete\": true"), std::string::npos);
    EXPECT_EQ(json_number(summary_one, "mpi_ranks"), 1);
    EXPECT_EQ(json_number(summary_two, "mpi_ranks"), 2);
    EXPECT_NE(summary_two.find("\"invariant_violations\": []"), std::string::npos) << summary_two;
    const double its_one = json_number(summary_one, "total_newton_iterations"),
                 its_two = json_number(summary_two, "total_newton_iterations");
    EXPECT_GT(its_one, 0);
    EXPECT_LE(std::abs(its_two - its_one), 0.1 * its_one) << its_one << " against " << its_two;
    EXPECT_EQ(file_names(serial), file_names(shared));

    // A run stopped after its last checkpoint, before its summary said so, resumes on two
    // processes: the writer rewrites the outputs while the other process waits, and both
    // finish the run.
    std::string unfinished = summary_two;
    unfinished.replace(unfinished.find("\"complete\": true"), 16, "\"complete\": false");
    write_file(shared + "/summary.json", unfinished);
    const RunResult resumed = run_on_two_processes(name + "-shared.prm --resume");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("resuming after step"), std::string::npos) << resumed.output;
    EXPECT_NE(read_file(shared + "/summary.json").find("\"complete\": true"), std::string::npos);

    const CsvTable a = last_nodes(serial), b = last_nodes(shared);
    ASSERT_EQ(a.header, b.header);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    double largest = 0;
    for (std::size_t r = 0; r < a.rows.size(); ++r)
      for (std::size_t c = 0; c < a.header.size(); ++c)
        if (a.header[c].rfind("x_", 0) == 0)
          largest = std::max(largest, std::abs(a.rows[r][c] - b.rows[r][c]));
    EXPECT_LE(largest, tolerance) << name << ": final positions differ by " << largest;
  }

  // The shared run's solver, and the Newton variant of both runs: with the direct solver the
  // default trust region, with amg projected Newton (what the trust region becomes with it).
  std::string distributed_solver(const std::string &solver)
  {
    return "subsection Solver\n  set distributed solver = " + solver + "\n" +
           (solver == "amg" ? "  set hessian projection = always\n" : "") + "end\n";
  }
} // namespace

TEST(DistributedRuns, BallOnSpikes2dWithFrictionMatchesSerial)
{
  // The default scene cut to its first 0.3 s: the ball lands on the spikes at ~0.14 s.
  std::string scene = read_file(source_dir() + "/prm/default.prm");
  scene             = with_entry(scene, "end time", "0.3");
  scene             = with_entry(scene, "output directory", "OUTPUT");
  scene             = with_entry(scene, "output every", "10");
  scene += "set write nodal csv = true\n" + distributed_solver("direct");
  // Newton stops at |dx|_inf < 1e-5 h L (h = 0.01, L the ball's bounding-box diagonal): the
  // direct solver's run agrees within that (measured: to 3e-15, with the trust region).
  expect_shared_run_matches_serial("ball_2d", scene, 1e-5 * 0.01 * std::sqrt(2.0));
}

TEST(DistributedRuns, BallOnSpikes3dWithFrictionMatchesSerial)
{
  std::string scene = read_file(source_dir() + "/prm/verification/ball_on_spikes_3d.prm");
  scene             = with_entry(scene, "end time", "0.15");
  scene             = with_entry(scene, "output directory", "OUTPUT");
  scene             = with_entry(scene, "output every", "5");
  scene = replaced(scene, "set dhat = 1e-3", "set dhat = 1e-3\n  set friction coefficient = 0.3\n  set epsilon v = 1e-3");
  scene += "set write nodal csv = true\n" + distributed_solver("amg");
  // CG stops at a residual of 1e-12: each of the 15 steps ends within the Newton tolerance of
  // the serial one's (measured: 4e-7 apart at the end, 1e-10 with the direct solver).
  expect_shared_run_matches_serial("ball_3d", scene, 15 * 1e-5 * 0.01 * std::sqrt(3.0));
}

TEST(DistributedRuns, RefusesWhatNeedsOneProcess)
{
  fs::create_directories("output/distributed_runs");
  const auto expect_refused = [](const std::string &file, const std::string &entry) {
    const RunResult r = run_on_two_processes(file);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const std::regex error_line("ritr: error: [^\n]*" + entry + "[^\n]*\n");
    EXPECT_EQ(std::distance(std::sregex_iterator(r.output.begin(), r.output.end(), error_line), std::sregex_iterator()),
              1)
      << r.output;
    EXPECT_EQ(r.output.find("ritr: error:"), r.output.rfind("ritr: error:")) << r.output;
  };
  write_file("shared-ritr.prm",
             replaced(read_file(source_dir() + "/prm/ritr_ball_on_spikes_2d.prm"), "set output directory",
                      "set output directory = output/distributed_runs/ritr\n# "));
  expect_refused("shared-ritr.prm", "Adaptivity/enabled");
  EXPECT_FALSE(fs::exists("output/distributed_runs/ritr"));
  write_file("shared-exact.prm", replaced(small_scene, "OUTPUT", "output/distributed_runs/exact") +
                                   "subsection Solver\n  set hessian projection = never\nend\n");
  expect_refused("shared-exact.prm", "Solver/hessian projection");
}
