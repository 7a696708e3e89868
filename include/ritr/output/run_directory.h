#pragma once
// The output directory of a run. It is checked before anything is written (bad input must
// leave it untouched), then owned by the run from its start: the previous run's outputs are
// removed, so that a killed run never mixes with an older one or looks complete.
#include <ritr/output/vtk_files.h>

#include <filesystem>
#include <sstream>
#include <string>

namespace ritr
{
  // Whether `name` is a file that a run writes, or its temporary (NAME.tmp): summary.json,
  // log.csv, newton.csv, checkpoint.bin, the .pvd collections,
  // solution-/reference-/obstacles-NNNNN.vtu, nodes-NNNNN.csv.
  bool is_run_output(const std::string &name);

  // STEM-NNNNN.EXT: the file of step n (five digits at least).
  std::string numbered_output(const std::string &stem, unsigned int n, const std::string &extension);

  // Why `directory` cannot hold a run's outputs ("" when it can); touches nothing.
  std::string output_directory_problem(const std::filesystem::path &directory);

  // The files a run keeps extending: the .pvd collections, and log.csv's rows.
  struct RunOutputs
  {
    explicit RunOutputs(const std::filesystem::path &directory)
      : directory(directory)
      , solution((directory / "solution.pvd").string())
      , reference((directory / "reference.pvd").string())
      , obstacles((directory / "obstacles.pvd").string())
    {}

    std::filesystem::path directory;
    PvdCollection         solution, reference, obstacles;
    std::ostringstream    log;
    std::ostringstream    newton_log;  // newton.csv, when the scene asks for it
    double                output_seconds = 0;  // spent writing the per-step files
  };

  // Removes the previous run's outputs and stale temporaries except summary.json, which the
  // new run has already replaced. The checkpoint goes first, so that no resume builds on
  // frames that are going, then the .pvd collections, so that none names a removed file.
  void remove_previous_outputs(const std::filesystem::path &directory);

  // A resumed run's clean-up: removes the per-frame files of steps after `step` (a killed
  // run wrote them past its last checkpoint; the resumed run writes them again) and stale
  // temporaries. Call it once the .pvd collections no longer name those files.
  void remove_outputs_after(const std::filesystem::path &directory, unsigned int step);
} // namespace ritr
