// A run owns its output directory: a second run, or a resume, started in it while the first
// runs is refused with one line naming the directory and the first run's process, and the
// first run ends as if it had been alone. The lock dies with its process: a killed run's
// lock file blocks nobody.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <regex>
#include <thread>

#include "run_ritr.h"

using namespace ritr::test_support;
namespace fs = std::filesystem;

namespace
{
  const std::string folder = "output/output_directory_lock";

  // The small scene made long enough (100 steps of a finer strip) to be caught while it runs,
  // writing to `output`.
  std::string long_scene(const std::string &output)
  {
    return replaced(replaced(replaced(small_scene, "OUTPUT", output), "set end time = 0.02", "set end time = 1"),
                    "set subdivisions = 4, 1", "set subdivisions = 40, 8");
  }

  std::string write_scene(const std::string &name, const std::string &text)
  {
    const std::string file = folder + "/" + name + ".prm";
    write_file(file, text);
    return file;
  }

  // Waits until the run `pid` holds `output` (its lock file names it); false if it ended first.
  bool wait_for_lock(const pid_t pid, const std::string &output)
  {
    const std::string expected = std::to_string(pid) + "\n";
    while (read_file(output + "/ritr.lock") != expected)
      {
        if (waitpid(pid, nullptr, WNOHANG) == pid)
          return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    return true;
  }

  bool still_running(const pid_t pid) { return waitpid(pid, nullptr, WNOHANG) == 0; }


  // Every file each .pvd collection of `output` names exists.
  void expect_collections_complete(const std::string &output)
  {
    for (const char *pvd : {"/solution.pvd", "/reference.pvd", "/obstacles.pvd"})
      {
        const std::string text = read_file(output + pvd);
        const std::regex  dataset("file=\"([^\"]+)\"");
        unsigned int      n = 0;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it, ++n)
          EXPECT_TRUE(fs::exists(output + "/" + (*it)[1].str())) << pvd << " names a missing " << (*it)[1];
        EXPECT_EQ(n, 101u) << pvd;
      }
  }
} // namespace

TEST(OutputDirectoryLock, SecondRunAndResumeAreRefusedWhileTheFirstRuns)
{
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string alone = folder + "/alone", shared = folder + "/shared";
  const std::string first = write_scene("first", long_scene(shared));
  // The same run alone, to compare with.
  ASSERT_EQ(run_ritr(write_scene("alone", long_scene(alone))).exit_code, 0);

  const pid_t pid = start_ritr({first});
  ASSERT_TRUE(wait_for_lock(pid, shared)) << "the first run ended before it held its directory";
  // Paused while the others try, so that the overlap does not depend on the machine's speed.
  ASSERT_EQ(kill(pid, SIGSTOP), 0);
  // Another scene in the same directory, and a resume of the first: both refused at once.
  const std::string second   = write_scene("second", replaced(small_scene, "OUTPUT", shared));
  const std::string expected = "output directory: '" + shared + "' is in use by another ritr run (process " +
                               std::to_string(pid) + ")\n";
  for (const std::string &arguments : {second, first + " --resume"})
    {
      const RunResult r = run_ritr(arguments, "2>&1 >" + folder + "/refused.stdout");
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_EQ(read_file(folder + "/refused.stdout"), "") << arguments;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_EQ(r.output.rfind("ritr: error: " + arguments.substr(0, arguments.find(' ')) + ":4: ", 0), 0u) << r.output;
      EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    }
  ASSERT_TRUE(still_running(pid)) << "the first run ended before the others were refused: the test saw no overlap";
  ASSERT_EQ(kill(pid, SIGCONT), 0);
  EXPECT_EQ(exit_code_of(pid), 0);

  // The first run's results are those of the run alone, every frame in place; its lock is gone.
  EXPECT_NE(read_file(shared + "/summary.json").find("\"complete\": true"), std::string::npos);
  const auto energy = csv_column(shared + "/log.csv", "energy"), energy_alone = csv_column(alone + "/log.csv", "energy");
  ASSERT_EQ(energy.size(), 100u);
  ASSERT_EQ(energy_alone.size(), 100u);
  for (std::size_t i = 0; i < energy.size(); ++i)
    EXPECT_NEAR(energy[i], energy_alone[i], 1e-10 * std::abs(energy_alone[i])) << "step " << i + 1;
  expect_collections_complete(shared);
  EXPECT_FALSE(fs::exists(shared + "/ritr.lock"));
}

TEST(OutputDirectoryLock, KilledRunsLockBlocksNobody)
{
  const std::string killed = folder + "/killed";
  fs::remove_all(killed);
  fs::create_directories(folder);
  const std::string scene = write_scene("killed", long_scene(killed));
  const pid_t       pid   = start_ritr({scene});
  ASSERT_TRUE(wait_for_lock(pid, killed)) << "the run ended before it held its directory";
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  // The lock file stays behind, naming a process that is gone; the next run takes over.
  ASSERT_EQ(read_file(killed + "/ritr.lock"), std::to_string(pid) + "\n");
  const RunResult r = run_ritr(write_scene("after_kill", replaced(small_scene, "OUTPUT", killed)));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read_file(killed + "/summary.json").find("\"complete\": true"), std::string::npos);
  EXPECT_FALSE(fs::exists(killed + "/ritr.lock"));
}
