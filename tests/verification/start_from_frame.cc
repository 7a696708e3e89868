// `start from`: a run that starts from another run's frame. On the same mesh it continues that
// run (the same positions to round-off, through contact and friction); on a refined mesh it
// starts from the coarse state itself (every fine node where the coarse piecewise-linear
// positions and velocities put it); bad input is refused with one line naming the entry, exit
// code 2, before anything is written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include <ritr/output/vtk_reader.h>

#include <set>

#include "run_ritr.h"

using namespace ritr::test_support;
namespace fs = std::filesystem;

namespace
{
  const std::string folder = "output/start_from_frame";

  // The fixed-mesh ball on spikes, thrown down so that it reaches the spikes in the first
  // steps (contact and friction from step 3 on), a frame with nodal CSV at every step.
  std::string ball_scene(const std::string &output, const std::string &extra = "")
  {
    std::string text = read_file(source_dir() + "/prm/verification/ball_on_spikes_2d.prm");
    text = std::regex_replace(text, std::regex("set end time *=[^\n]*"), "set end time = 0.1");
    text = std::regex_replace(text, std::regex("set output every *=[^\n]*"), "set output every = 1");
    text = std::regex_replace(text, std::regex("set output directory *=[^\n]*"), "set output directory = " + output);
    text = std::regex_replace(text, std::regex("set center *=[^\n]*"), "set center = 0, 0.702");
    return text + "set write nodal csv = true\nsubsection Body 0\n  set initial velocity = 0; -1\nend\n" + extra;
  }

  std::string write_scene(const std::string &name, const std::string &text)
  {
    const std::string file = folder + "/" + name + ".prm";
    write_file(file, text);
    return file;
  }

  std::string frame(const std::string &run, const unsigned int step)
  {
    char name[32];
    std::snprintf(name, sizeof name, "/solution-%05u.vtu", step);
    return fs::absolute(run + name).string();
  }

  std::string nodes(const std::string &run, const unsigned int step)
  {
    char name[32];
    std::snprintf(name, sizeof name, "/nodes-%05u.csv", step);
    return run + name;
  }

  // Columns u_x, u_y, x_x, x_y, v_x, v_y of a nodal CSV, one row per node.
  std::vector<std::array<double, 6>> node_rows(const std::string &file)
  {
    const CsvTable t = read_csv(file);
    std::vector<std::array<double, 6>> rows;
    const char *names[] = {"u_x", "u_y", "x_x", "x_y", "v_x", "v_y"};
    for (const auto &r : t.rows)
      {
        std::array<double, 6> row;
        for (int k = 0; k < 6; ++k)
          {
            EXPECT_LT(t.column(names[k]), t.header.size()) << names[k];
            row[k] = r[t.column(names[k])];
          }
        rows.push_back(row);
      }
    return rows;
  }

  std::vector<double> log_column(const std::string &run, const std::string &name)
  {
    return csv_column(run + "/log.csv", name);
  }
} // namespace

TEST(StartFromFrame, OnTheSameMeshItContinuesTheRun)
{
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string whole = folder + "/whole", continued = folder + "/continued";
  const RunResult   a = run_ritr(write_scene("whole", ball_scene(whole)));
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(log_column(whole, "time").size(), 10u);
  ASSERT_LT(log_column(whole, "min_distance")[3], 1e-3) << "the ball must be in contact after the start frame";

  constexpr unsigned int start = 2;
  const RunResult b = run_ritr(write_scene("continued", ball_scene(continued, "set start from = " + frame(whole, start) + "\n")));
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find("8 steps from t = 0.02"), std::string::npos) << b.output;

  // Its step k is the whole run's step start + k, at the same time.
  const std::vector<double> times = log_column(continued, "time"), whole_times = log_column(whole, "time");
  ASSERT_EQ(times.size(), 8u);
  for (unsigned int k = 0; k < times.size(); ++k)
    EXPECT_NEAR(times[k], whole_times[start + k], 1e-14);
  double largest = 0;
  for (unsigned int k = 0; k <= 8; ++k)
    {
      const auto mine = node_rows(nodes(continued, k)), theirs = node_rows(nodes(whole, start + k));
      ASSERT_EQ(mine.size(), theirs.size());
      for (std::size_t i = 0; i < mine.size(); ++i)
        for (int c = 0; c < 6; ++c)
          largest = std::max(largest, std::abs(mine[i][c] - theirs[i][c]));
    }
  std::cout << "largest difference of u, x, v over 8 steps: " << largest << std::endl;
  EXPECT_LT(largest, 1e-9);
  const auto frames = ritr::read_pvd(continued + "/solution.pvd");
  ASSERT_EQ(frames.size(), 9u);
  EXPECT_NEAR(frames.front().time, 0.02, 1e-15);
  EXPECT_NEAR(frames.back().time, 0.1, 1e-15);
}

TEST(StartFromFrame, ARefinedMeshStartsFromTheCoarseState)
{
  const std::string coarse = folder + "/whole", fine = folder + "/refined";
  ASSERT_TRUE(fs::exists(frame(coarse, 4))) << "runs after OnTheSameMeshItContinuesTheRun";
  const RunResult r = run_ritr(write_scene(
    "refined", ball_scene(fine, "set start from = " + frame(coarse, 4) + "\nset end time = 0.05\n"
                                "subsection Body 0\n  set refinements = 1\nend\n")));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Edge subdivision puts every fine node on a coarse node or the midpoint of a coarse edge; the
  // coarse state is linear along the edge, so the fine node starts at the midpoint's state.
  const auto coarse_nodes = node_rows(nodes(coarse, 4)), fine_nodes = node_rows(nodes(fine, 0));
  ASSERT_GT(fine_nodes.size(), 3 * coarse_nodes.size());
  std::set<std::pair<unsigned int, unsigned int>> edges;
  for (const auto &cell : ritr::read_vtu(frame(coarse, 4)).cells)
    for (std::size_t i = 0; i < cell.size(); ++i)
      for (std::size_t j = 0; j < cell.size(); ++j)
        edges.insert({cell[i], cell[j]});  // (a, a) too: a fine node on a coarse one
  double       largest = 0;
  unsigned int matched = 0;
  for (const auto &f : fine_nodes)
    for (const auto &[a, b] : edges)
      {
        const auto &p = coarse_nodes[a], &q = coarse_nodes[b];
        if (a > b || std::abs(f[0] - 0.5 * (p[0] + q[0])) > 1e-12 || std::abs(f[1] - 0.5 * (p[1] + q[1])) > 1e-12)
          continue;
        ++matched;
        for (int c = 2; c < 6; ++c)
          largest = std::max(largest, std::abs(f[c] - 0.5 * (p[c] + q[c])));
        break;
      }
  EXPECT_EQ(matched, fine_nodes.size());
  std::cout << "largest difference from the coarse state at the fine nodes: " << largest << std::endl;
  EXPECT_LT(largest, 1e-12);
  EXPECT_EQ(log_column(fine, "time").size(), 1u);
}

TEST(StartFromFrame, BadFramesAreRefusedNamingTheEntry)
{
  const std::string coarse = folder + "/whole";
  ASSERT_TRUE(fs::exists(frame(coarse, 10))) << "runs after OnTheSameMeshItContinuesTheRun";
  write_file(folder + "/not_listed.vtu", read_file(frame(coarse, 3)));
  const std::vector<std::pair<std::string, std::string>> cases = {
    {"set start from = " + folder + "/nowhere/solution-00001.vtu\n", "no such file"},
    {"set start from = " + frame(coarse, 10) + "\n", "leaves no step before the end time"},
    {"set start from = " + fs::absolute(folder + "/not_listed.vtu").string() + "\n", "is not listed in"},
    {"set start from = " + frame(coarse, 2) + "\nset mode = static\n", "needs a dynamic scene"},
    {"set start from = " + frame(coarse, 2) + "\nsubsection Body 0\n  set radius = 0.6\nend\n",
     "lies outside the reference domain of"},
  };
  for (const auto &[extra, message] : cases)
    {
      const std::string output = folder + "/refused";
      fs::remove_all(output);
      const RunResult r = run_ritr(write_scene("refused", ball_scene(output, extra)));
      EXPECT_EQ(r.exit_code, 2) << extra << r.output;
      EXPECT_NE(r.output.find("start from"), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_FALSE(fs::exists(output)) << extra;
    }
}
