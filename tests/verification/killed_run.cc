// A run killed (SIGKILL) at random moments in a directory that held a complete run: every
// file left is well formed, every .pvd names only files that exist, nothing of the new run
// sits beside the old run's files, and a summary says "complete": true only when every step
// is there (the old run, if killed before the new run took the directory over). Resumed, the
// killed run ends complete, whatever moment the kill came at.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <random>
#include <regex>
#include <thread>

#include "run_ritr.h"

using namespace ritr::test_support;
namespace fs = std::filesystem;

namespace
{
  const std::string folder = "output/killed_run", output = folder + "/out", scene = folder + "/scene.prm";

  // The small scene, long enough (30 steps, about a second) to be killed while it runs.
  const std::string scene_text =
    replaced(replaced(replaced(small_scene, "OUTPUT", output), "set end time = 0.02", "set end time = 0.3"),
             "set subdivisions = 4, 1", "set subdivisions = 40, 8");

  bool ends_with(const std::string &s, const std::string &end)
  {
    return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
  }

  // The files of a snapshot without temporaries (a temporary may be torn; the next run
  // removes it).
  std::map<std::string, std::string> without_temporaries(std::map<std::string, std::string> files)
  {
    for (auto it = files.begin(); it != files.end();)
      it = ends_with(it->first, ".tmp") ? files.erase(it) : std::next(it);
    return files;
  }

  // Checks what a killed run left; `old_run` is the complete run the directory held before.
  void check_left_files(const std::map<std::string, std::string> &old_run)
  {
    const auto files = without_temporaries(snapshot(output));
    if (files == without_temporaries(old_run))
      return;  // killed before the new run took the directory over: the old run is intact
    int  rows = -1;  // log.csv rows, if it exists
    bool claims_complete = false;
    for (const auto &[path, text] : files)
      {
        const std::string name = fs::path(path).filename().string();
        if (ends_with(name, ".vtu") || ends_with(name, ".pvd"))
          {
            EXPECT_TRUE(ends_with(text, "</VTKFile>\n")) << path << " is torn";
          }
        if (name == "summary.json")
          {
            EXPECT_TRUE(ends_with(text, "}\n")) << path << " is torn";
            claims_complete = text.find("\"complete\": true") != std::string::npos;
            EXPECT_TRUE(claims_complete || text.find("\"complete\": false") != std::string::npos) << text;
          }
        if (name == "log.csv")
          {
            ASSERT_TRUE(ends_with(text, "\n")) << "torn log.csv";
            std::istringstream lines(text);
            std::string        header, row;
            std::getline(lines, header);
            rows = 0;
            for (; std::getline(lines, row); ++rows)
              EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ','));
          }
        if (ends_with(name, ".pvd"))
          {
            const std::regex dataset("file=\"([^\"]+)\"");
            for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it)
              EXPECT_TRUE(fs::exists(output + "/" + (*it)[1].str())) << path << " names a missing " << (*it)[1];
          }
      }
    if (claims_complete)
      {
        EXPECT_EQ(rows, 30) << "summary.json claims a complete run";
        EXPECT_TRUE(files.count(output + "/solution-00030.vtu")) << "summary.json claims a complete run";
      }
    // Step N's files are written after log.csv has its row: a later step is the old run's.
    if (rows >= 0)
      for (const auto &[path, text] : files)
        {
          const std::string name = fs::path(path).filename().string();
          if (name.rfind("solution-", 0) == 0 && ends_with(name, ".vtu"))
            {
              EXPECT_LE(std::stoi(name.substr(9, 5)), rows) << name << " is left from the old run";
            }
        }
  }

  // Resumes what a kill left: the run ends complete, as a run that was never stopped would --
  // every step in log.csv, every frame its collections name in place, the summary with its
  // energy terms -- unless the kill came before the run's first checkpoint (nothing to resume
  // from) or before it took the directory over (the old run, complete, is left alone).
  void check_resumed_run()
  {
    const RunResult r = run_ritr(scene + " --resume");
    if (r.exit_code == 2)
      {
        EXPECT_NE(r.output.find("checkpoint.bin: no checkpoint to resume from"), std::string::npos) << r.output;
        return;
      }
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string summary = read_file(output + "/summary.json");
    EXPECT_NE(summary.find("\"complete\": true"), std::string::npos) << summary;
    EXPECT_NE(summary.find("\"final_energy_terms\": {\""), std::string::npos) << summary;
    const std::string log = read_file(output + "/log.csv");
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 31) << "30 steps and the header";
    for (const char *pvd : {"/solution.pvd", "/reference.pvd", "/obstacles.pvd"})
      {
        const std::string text = read_file(output + pvd);
        const std::regex  dataset("file=\"([^\"]+)\"");
        unsigned int      frames = 0;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it, ++frames)
          EXPECT_TRUE(fs::exists(output + "/" + (*it)[1].str())) << pvd << " names a missing " << (*it)[1];
        EXPECT_EQ(frames, 31u) << pvd;
      }
    EXPECT_FALSE(fs::exists(output + "/ritr.lock"));
  }
} // namespace

TEST(KilledRun, LeavesWellFormedFilesAndNoFalseClaimOfCompletion)
{
  fs::remove_all(folder);
  fs::create_directories(folder);
  write_file(scene, scene_text);
  const auto      start = std::chrono::steady_clock::now();
  const RunResult full  = run_ritr(scene);
  const double    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(full.exit_code, 0) << full.output;
  write_file(output + "/solution-00099.vtu.tmp", "a stale temporary");
  const auto old_run = snapshot(output);

  const unsigned int seed = std::random_device()();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937                           random(seed);
  std::uniform_real_distribution<double> moment(0, seconds);
  for (int kill_count = 0; kill_count < 10; ++kill_count)
    {
      // Each run starts from the old complete run.
      fs::remove_all(output);
      fs::create_directories(output);
      for (const auto &[path, text] : old_run)
        write_file(path, text);
      const double at  = moment(random);
      const pid_t  pid = start_ritr({scene});
      std::this_thread::sleep_for(std::chrono::duration<double>(at));
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
      SCOPED_TRACE("killed after " + std::to_string(at) + " s");
      check_left_files(old_run);
      check_resumed_run();
    }
}
