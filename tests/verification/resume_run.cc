// `ritr SCENE.prm --resume`: a run killed (SIGKILL) between two checkpoints and resumed, twice,
// ends where the uninterrupted run ends -- the same positions in every frame, the same
// log.csv, newton.csv, collections and summary totals -- and a checkpoint that is missing,
// damaged or of another scene is refused with one line and exit code 2, touching nothing; a run
// stopped on the Newton cap or at its end time goes on with a larger one.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <regex>
#include <thread>

#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include "run_ritr.h"

using namespace ritr::test_support;
namespace fs = std::filesystem;

namespace
{
  const std::string folder = "output/resume_run";

  // `text` with the value of its first `set NAME = ...` replaced.
  std::string with_entry(const std::string &text, const std::string &name, const std::string &value)
  {
    const std::regex entry("set " + name + " *=[^\n]*");
    EXPECT_TRUE(std::regex_search(text, entry)) << name;
    return std::regex_replace(text, entry, "set " + name + " = " + value, std::regex_constants::format_first_only);
  }

  // A short ball-on-spikes (r-adaptivity, contact, friction): 10 steps, a frame and a
  // checkpoint every third and at the end, the ball thrown down so that it touches the
  // spikes early; the default outer solve (quasi-Newton), whose curvature and trust region
  // carry over from step to step and so through the checkpoint.
  std::string ball_scene(const std::string &output)
  {
    std::string text = read_file(source_dir() + "/prm/ritr_ball_on_spikes_2d.prm");
    text             = with_entry(text, "end time", "0.1");
    text             = with_entry(text, "output every", "3");
    text             = with_entry(text, "output directory", output);
    return text + "set write nodal csv = true\n"
                  "subsection Body 0\n  set initial velocity = 0; -2\nend\n"
                  "subsection Solver\n  set newton log = true\nend\n";
  }
  constexpr unsigned int n_steps = 10, output_every = 3;

  std::string write_scene(const std::string &name, const std::string &text)
  {
    const std::string file = folder + "/" + name + ".prm";
    write_file(file, text);
    return file;
  }

  unsigned int log_rows(const std::string &directory)
  {
    const std::string text = read_file(directory + "/log.csv");
    return text.empty() ? 0 : std::count(text.begin(), text.end(), '\n') - 1;
  }

  // Starts ritr on `scene`, waits until its log.csv has at least `rows` rows and a checkpoint
  // exists, and kills it with SIGKILL. False if the run ended before.
  bool run_and_kill(const std::string &scene, const std::string &output, const unsigned int rows,
                    const bool resume)
  {
    const pid_t pid    = resume ? start_ritr({scene, "--resume"}) : start_ritr({scene});
    int         status = 0;
    bool        ended  = false;
    while (!(ended = waitpid(pid, &status, WNOHANG) == pid) &&
           (log_rows(output) < rows || !fs::exists(output + "/checkpoint.bin")))
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (ended)
      return false;
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return true;
  }

  // The numbers of a CSV file's rows.
  std::vector<std::vector<double>> numbers(const std::string &file) { return read_csv(file).rows; }

  // Largest difference between the same numbers of two tables.
  double max_difference(const std::vector<std::vector<double>> &a, const std::vector<std::vector<double>> &b)
  {
    EXPECT_EQ(a.size(), b.size());
    double d = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
      for (std::size_t j = 0; j < std::min(a[i].size(), b[i].size()); ++j)
        d = std::max(d, std::abs(a[i][j] - b[i][j]));
    return d;
  }

  std::string summary_entry(const std::string &directory, const std::string &name)
  {
    const std::string text = read_file(directory + "/summary.json");
    std::smatch       m;
    EXPECT_TRUE(std::regex_search(text, m, std::regex("\"" + name + "\": ([^,\n]*)"))) << name << '\n' << text;
    return m[1];
  }

  // Largest difference of u, x and v between two runs' nodal CSV frames at `steps`.
  double largest_node_difference(const std::string &a, const std::string &b, const std::vector<unsigned int> &steps)
  {
    double largest = 0;
    for (const unsigned int s : steps)
      {
        char name[32];
        std::snprintf(name, sizeof(name), "/nodes-%05u.csv", s);
        largest = std::max(largest, max_difference(numbers(a + name), numbers(b + name)));
      }
    return largest;
  }

  // `resumed`'s log.csv has each of the steps 1..n_steps once, with `whole`'s energies (12 digits).
  void expect_same_steps(const std::string &whole, const std::string &resumed, const unsigned int n_steps)
  {
    std::vector<double> steps;
    for (unsigned int s = 1; s <= n_steps; ++s)
      steps.push_back(s);
    EXPECT_EQ(csv_column(resumed + "/log.csv", "step"), steps);
    const auto energy_a = csv_column(whole + "/log.csv", "energy"), energy_b = csv_column(resumed + "/log.csv", "energy");
    ASSERT_EQ(energy_a.size(), energy_b.size());
    for (std::size_t i = 0; i < energy_a.size(); ++i)
      EXPECT_NEAR(energy_a[i], energy_b[i], 1e-10 * std::abs(energy_a[i])) << "step " << i + 1;
  }
} // namespace

TEST(ResumeRun, KilledAndResumedRunMatchesTheUninterruptedOne)
{
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string whole = folder + "/whole", killed = folder + "/killed";
  const RunResult   full = run_ritr(write_scene("whole", ball_scene(whole)));
  ASSERT_EQ(full.exit_code, 0) << full.output;

  // Killed twice after a few steps, each kill past a checkpoint; resumed after each.
  const std::string scene = write_scene("killed", ball_scene(killed));
  ASSERT_TRUE(run_and_kill(scene, killed, 4, false)) << "the run ended before it could be killed";
  const unsigned int first_kill_rows = log_rows(killed);
  ASSERT_LT(first_kill_rows, 7u);
  ASSERT_TRUE(run_and_kill(scene, killed, 7, true)) << "the resumed run ended before the kill";
  std::cout << "killed after " << first_kill_rows << " and " << log_rows(killed) << " steps" << std::endl;
  const RunResult resumed = run_ritr(scene + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  std::smatch resumed_after;
  ASSERT_TRUE(std::regex_search(resumed.output, resumed_after, std::regex("resuming after step (\\d+)/10")))
    << resumed.output;
  EXPECT_EQ(std::stoi(resumed_after[1]) % output_every, 0u) << "a checkpoint with every frame";
  EXPECT_LT(std::stoi(resumed_after[1]), 9) << "killed before the step 9 frame";

  // Positions, velocities and reference positions of every frame (17 digits).
  std::vector<unsigned int> frames;
  for (unsigned int s = 0; s <= n_steps; ++s)
    if (s % output_every == 0 || s == n_steps)
      frames.push_back(s);
  const double largest = largest_node_difference(whole, killed, frames);
  std::cout << "largest difference of u, x, v between the resumed and the uninterrupted run: " << largest
            << std::endl;
  EXPECT_LE(largest, 1e-12);
  expect_same_steps(whole, killed, n_steps);
  // newton.csv: the same iterations, each once.
  for (const char *c : {"step", "solve", "iteration"})
    EXPECT_EQ(csv_column(whole + "/newton.csv", c), csv_column(killed + "/newton.csv", c)) << c;
  EXPECT_LE(max_difference(numbers(whole + "/newton.csv"), numbers(killed + "/newton.csv")), 1e-9);

  // Every frame once in each collection, at the same times.
  for (const char *pvd : {"/solution.pvd", "/reference.pvd", "/obstacles.pvd"})
    EXPECT_EQ(read_file(whole + pvd), read_file(killed + pvd)) << pvd;

  EXPECT_EQ(summary_entry(killed, "complete"), "true");
  for (const char *entry : {"steps", "final_energy", "total_newton_iterations", "total_outer_iterations",
                            "total_line_search_trials", "invariant_violations"})
    EXPECT_EQ(summary_entry(whole, entry), summary_entry(killed, entry)) << entry;

  const RunResult compare = run_command(std::string(RITR_COMPARE_BINARY) + " " + whole + " " + killed, "2>&1");
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  std::smatch hausdorff;
  ASSERT_TRUE(std::regex_search(compare.output, hausdorff, std::regex("\"max_hausdorff\": ([^,]*)")));
  EXPECT_LE(std::stod(hausdorff[1]), 1e-12) << compare.output;

  // A finished run has nothing left to resume: it says so and touches nothing.
  const auto before = snapshot(killed);
  const RunResult again = run_ritr(scene + " --resume");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("already complete"), std::string::npos) << again.output;
  EXPECT_EQ(snapshot(killed), before);
}

namespace
{
  // 64-bit FNV-1a, the checkpoint's checksum.
  std::uint64_t fnv1a(const std::string &bytes)
  {
    std::uint64_t hash = 14695981039346656037ull;
    for (const unsigned char c : bytes)
      hash = (hash ^ c) * 1099511628211ull;
    return hash;
  }

  // `checkpoint` with its time replaced and its checksum recomputed. The layout: a 24-byte
  // header ("RITRCKPT", version, byte-order mark, payload size), then the payload -- u32
  // dimension, u64 scene fingerprint, u32 step, f64 time, ... -- and the checksum of the
  // payload in its last 8 bytes.
  std::string with_time(std::string checkpoint, const double time)
  {
    constexpr std::size_t header = 24, time_at = header + 4 + 8 + 4;
    std::memcpy(&checkpoint[time_at], &time, sizeof(time));
    const std::uint64_t checksum = fnv1a(checkpoint.substr(header, checkpoint.size() - header - 8));
    std::memcpy(&checkpoint[checkpoint.size() - 8], &checksum, sizeof(checksum));
    return checkpoint;
  }

  // Resumes `scene` whose output directory holds `checkpoint` (none if empty): one line
  // naming the checkpoint with `words`, exit code 2, no file touched.
  void expect_refused(const std::string &name, const std::string &scene_text, const std::string &checkpoint,
                      const std::string &words)
  {
    const std::string output = folder + "/" + name;
    fs::create_directories(output);
    write_file(output + "/log.csv", "previous results\n");
    if (!checkpoint.empty())
      write_file(output + "/checkpoint.bin", checkpoint);
    const std::string scene  = write_scene(name, replaced(scene_text, "OUTPUT", output));
    const auto        before = snapshot(output);
    const RunResult   r      = run_ritr(scene + " --resume");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(output + "/checkpoint.bin"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
    EXPECT_EQ(snapshot(output), before);
  }
} // namespace

TEST(ResumeRun, RefusesMissingDamagedOrForeignCheckpoints)
{
  fs::remove_all(folder + "/bad");
  fs::create_directories(folder + "/bad");
  const std::string good_output = folder + "/bad/good";
  const RunResult   good = run_ritr(write_scene("bad/good", replaced(small_scene, "OUTPUT", good_output)));
  ASSERT_EQ(good.exit_code, 0) << good.output;
  const std::string checkpoint = read_file(good_output + "/checkpoint.bin");
  ASSERT_GT(checkpoint.size(), 100u);

  expect_refused("bad/missing", small_scene, "", "no checkpoint");
  expect_refused("bad/truncated", small_scene, checkpoint.substr(0, checkpoint.size() / 2), "truncated");
  std::string flipped = checkpoint;
  flipped[flipped.size() / 2] ^= 0x10;
  expect_refused("bad/corrupted", small_scene, flipped, "corrupted");
  expect_refused("bad/not_a_checkpoint", small_scene, "step,time\n1,0.01\n", "not a ritr checkpoint");
  // Contents no run writes, under a checksum that matches them.
  expect_refused("bad/time_nan", small_scene, with_time(checkpoint, std::nan("")),
                 "is corrupted (its time is not a finite time)");
  expect_refused("bad/time_not_its_steps", small_scene, with_time(checkpoint, 0.015),
                 "is corrupted (its time is not its last step's)");
  // The refusal names the entry that differs.
  expect_refused("bad/other_scene", replaced(small_scene, "set dhat = 1e-3", "set dhat = 2e-3"), checkpoint,
                 "belongs to another scene (Contact/dhat is 2e-3 in ");
  // The same scene with its outputs elsewhere, run on other numbers of threads, with an
  // entry set to its default value, is the same run: entries left at their defaults do not
  // count, so that an entry a newer ritr declares keeps older checkpoints.
  const std::string moved = folder + "/bad/moved";
  fs::create_directories(moved);
  fs::copy(good_output, moved, fs::copy_options::recursive);
  const std::string moved_scene =
    replaced(small_scene, "OUTPUT", moved) + "subsection Solver\n  set threads = 1\n  set factorization threads = 2\n  set max iterations = 200\nend\n";
  const RunResult r = run_ritr(write_scene("bad/moved", moved_scene) + " --resume");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("already complete"), std::string::npos) << r.output;
}

// A checkpoint of a ritr whose scene listing held entries this one leaves out (the end time
// and the output directory, as ritr's listing did until those stopped counting) resumes: the
// entries are compared by value without them, the meshes by the checkpoint's own fingerprint.
// Changing a mesh is still refused.
TEST(ResumeRun, ResumesCheckpointsWhoseListingHoldsEntriesThatNoLongerCount)
{
  const std::string output = folder + "/older_listing";
  fs::remove_all(output);
  fs::create_directories(folder);
  const std::string scene_file = write_scene("older_listing", replaced(small_scene, "OUTPUT", output));
  {
    ritr::Scene scene = ritr::read_scene(scene_file);
    EXPECT_EQ(scene.parameter_listing.find("end time"), std::string::npos) << scene.parameter_listing;
    scene.parameter_listing = "set end time = 0.02\nset output directory = \n" + scene.parameter_listing;
    ritr::Simulation<2> simulation(scene);
    simulation.run();
  }
  ASSERT_EQ(summary_entry(output, "complete"), "true");
  const RunResult r = run_ritr(scene_file + " --resume");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("already complete"), std::string::npos) << r.output;

  const std::string other_mesh = write_scene("older_listing", replaced(replaced(small_scene, "OUTPUT", output),
                                                                       "subdivisions = 4, 1", "subdivisions = 5, 1"));
  const RunResult refused = run_ritr(other_mesh + " --resume");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("belongs to another scene (Body 0/subdivisions is 5, 1 in "), std::string::npos)
    << refused.output;
}

// The same entries with another mesh in the file they name: refused, naming the meshes.
TEST(ResumeRun, RefusesWhenTheMeshFileChanged)
{
  const std::string output = folder + "/mesh_file", mesh = folder + "/mesh_file.msh";
  fs::remove_all(output);
  fs::create_directories(folder);
  const std::string wedge = read_file(source_dir() + "/meshes/wedge.msh");
  write_file(mesh, wedge);
  const std::string scene = write_scene("mesh_file", replaced(replaced(small_scene, "OUTPUT", output),
                                                              "set shape = rectangle\n  set upper = 1, 0.2\n  set subdivisions = 4, 1",
                                                              "set shape = file\n  set file = " + fs::absolute(mesh).string()));
  const RunResult first = run_ritr(scene);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  // The wedge's apex moved by 1e-3.
  write_file(mesh, replaced(wedge, "\n1 0 0 0\n", "\n1 0.001 0 0\n"));
  const auto      before = snapshot(output);
  const RunResult r      = run_ritr(scene + " --resume");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("belongs to another scene (the meshes or initial state that " + scene + " gives differ)"),
            std::string::npos)
    << r.output;
  EXPECT_EQ(snapshot(output), before);
}

namespace
{
  // A finished run of the small scene in `output`, turned into what a run killed after its
  // last checkpoint but before its summary leaves: the summary of its start, which says
  // "complete": false. Returns the scene file.
  std::string killed_before_its_summary(const std::string &name, const std::string &output)
  {
    fs::remove_all(output);
    const std::string scene = write_scene(name, replaced(small_scene, "OUTPUT", output));
    const RunResult   r     = run_ritr(scene);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    write_file(output + "/summary.json", "{\n  \"complete\": false,\n  \"steps\": 0\n}\n");
    return scene;
  }
} // namespace

// A run killed between its last checkpoint and its summary has every step done: resumed, it
// writes the summary the finished run would have written, energy terms included.
TEST(ResumeRun, RunKilledBeforeItsSummaryEndsWithItsEnergyTerms)
{
  fs::create_directories(folder);
  const std::string output = folder + "/before_summary";
  const std::string scene  = killed_before_its_summary("before_summary", output);
  const RunResult   whole  = run_ritr(write_scene("whole_small", replaced(small_scene, "OUTPUT", folder + "/whole_small")));
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  const RunResult r = run_ritr(scene + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("resuming after step 2/2"), std::string::npos) << r.output;
  EXPECT_EQ(summary_entry(output, "complete"), "true");
  const std::string terms = "\"final_energy_terms\": \\{[^}]*\\}";
  std::smatch       resumed, uninterrupted;
  const std::string resumed_text = read_file(output + "/summary.json"), whole_text = read_file(folder + "/whole_small/summary.json");
  ASSERT_TRUE(std::regex_search(resumed_text, resumed, std::regex(terms))) << resumed_text;
  ASSERT_TRUE(std::regex_search(whole_text, uninterrupted, std::regex(terms))) << whole_text;
  EXPECT_EQ(resumed.str(), uninterrupted.str());
}

// The frames a checkpoint builds on must be there: a resume that would end "complete" with
// collections naming missing files is refused with one line naming the first, touching nothing.
TEST(ResumeRun, RefusesWhenFramesItBuildsOnAreMissing)
{
  fs::create_directories(folder);
  for (const std::string missing : {"solution-00002.vtu", "reference-00002.vtu", "obstacles-00001.vtu"})
    {
      const std::string output = folder + "/missing_" + missing.substr(0, missing.find('.'));
      const std::string scene  = killed_before_its_summary("missing_frame", output);
      fs::remove(output + "/" + missing);
      const auto      before = snapshot(output);
      const RunResult r      = run_ritr(scene + " --resume");
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_EQ(r.output.rfind("ritr: error: " + output + "/" + missing + ": is missing, and " + output +
                                 "/checkpoint.bin builds on it",
                               0),
                0u)
        << r.output;
      EXPECT_EQ(snapshot(output), before) << missing;
    }
}

// Nor is the Newton cap: a run stopped on it (exit code 3, the first contact step needs 11
// iterations) resumes with a larger one from its last checkpoint and ends where a run that
// never met the cap ends.
TEST(ResumeRun, RunStoppedOnTheNewtonCapResumesWithALargerOne)
{
  fs::create_directories(folder);
  const std::string uncapped = folder + "/uncapped", capped = folder + "/capped";
  fs::remove_all(uncapped);
  fs::remove_all(capped);
  const RunResult whole = run_ritr(write_scene("uncapped", ball_scene(uncapped)));
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  const RunResult stopped =
    run_ritr(write_scene("capped", ball_scene(capped) + "subsection Solver\n  set max iterations = 8\nend\n"));
  ASSERT_EQ(stopped.exit_code, 3) << stopped.output;
  EXPECT_NE(stopped.output.find("no convergence in 8 Newton iterations"), std::string::npos) << stopped.output;

  const RunResult r = run_ritr(write_scene("capped", ball_scene(capped)) + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("resuming after step 0/10"), std::string::npos) << r.output;
  EXPECT_LE(largest_node_difference(uncapped, capped, {0, 3, 6, 9, 10}), 1e-12);
  expect_same_steps(uncapped, capped, n_steps);
  EXPECT_EQ(summary_entry(capped, "complete"), "true");
}

// The end time is not part of the scene: a finished run resumed with a later end time goes
// on from its last step and ends where a run to that time ends, its collections holding the
// earlier end's frame besides the scene's; a checkpoint past the end time is refused.
TEST(ResumeRun, FinishedRunGoesOnToALaterEndTime)
{
  fs::create_directories(folder);
  const std::string longer = folder + "/longer", extended = folder + "/extended";
  const std::string longer_scene = with_entry(ball_scene(longer), "end time", "0.15");
  const RunResult   whole        = run_ritr(write_scene("longer", longer_scene));
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  fs::remove_all(extended);
  const RunResult first = run_ritr(write_scene("extended", ball_scene(extended)));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_EQ(summary_entry(extended, "complete"), "true");
  const std::string scene = write_scene("extended", with_entry(ball_scene(extended), "end time", "0.15"));
  const RunResult   r     = run_ritr(scene + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("resuming after step 10/15"), std::string::npos) << r.output;

  const double largest = largest_node_difference(longer, extended, {0, 3, 6, 9, 12, 15});
  std::cout << "largest difference of u, x, v between the extended run and the run to t = 0.15: " << largest
            << std::endl;
  EXPECT_LE(largest, 1e-12);
  expect_same_steps(longer, extended, 15);
  EXPECT_EQ(summary_entry(extended, "complete"), "true");
  EXPECT_EQ(summary_entry(extended, "steps"), "15");
  for (const char *entry : {"final_energy", "total_newton_iterations", "total_outer_iterations"})
    EXPECT_EQ(summary_entry(longer, entry), summary_entry(extended, entry)) << entry;

  // The collections: the run to t = 0.15's frames and the first part's last (step 10), once each.
  for (const std::string stem : {"solution", "reference", "obstacles"})
    {
      const std::string collection = read_file(extended + "/" + stem + ".pvd");
      for (const unsigned int s : {0u, 3u, 6u, 9u, 10u, 12u, 15u})
        {
          char name[48];
          std::snprintf(name, sizeof(name), "%s-%05u.vtu", stem.c_str(), s);
          const auto at = collection.find(name);
          EXPECT_NE(at, std::string::npos) << name << '\n' << collection;
          EXPECT_EQ(collection.find(name, at + 1), std::string::npos) << name << " twice";
        }
      const std::string uninterrupted = read_file(longer + "/" + stem + ".pvd");
      EXPECT_EQ(std::count(collection.begin(), collection.end(), '\n'),
                std::count(uninterrupted.begin(), uninterrupted.end(), '\n') + 1)
        << collection;
    }

  // Resumed once more, to a later end again: the frames of both earlier ends stay listed.
  const RunResult again = run_ritr(write_scene("extended", with_entry(ball_scene(extended), "end time", "0.17")) + " --resume");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("resuming after step 15/17"), std::string::npos) << again.output;
  const std::string solution = read_file(extended + "/solution.pvd");
  for (const char *name : {"solution-00010.vtu", "solution-00015.vtu", "solution-00017.vtu"})
    EXPECT_NE(solution.find(name), std::string::npos) << name << '\n' << solution;

  // Back to an earlier end time: refused with one line, nothing touched.
  const auto      before  = snapshot(extended);
  const RunResult shorter = run_ritr(write_scene("extended", ball_scene(extended)) + " --resume");
  EXPECT_EQ(shorter.exit_code, 2) << shorter.output;
  EXPECT_EQ(std::count(shorter.output.begin(), shorter.output.end(), '\n'), 1) << shorter.output;
  EXPECT_NE(shorter.output.find(extended + "/checkpoint.bin: is at step 17 (t = 0.17), past the end time of "),
            std::string::npos)
    << shorter.output;
  EXPECT_EQ(snapshot(extended), before);
}
