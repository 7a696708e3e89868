#pragma once
// Comparing two ritr runs frame by frame: the frames of the two solution.pvd series are paired
// by time, and each pair is compared by the Hausdorff distance of the deformed boundaries, the
// logged energies and the distance of the bodies' centroids.
#include <filesystem>
#include <optional>
#include <ostream>
#include <vector>

namespace ritr::compare
{
  struct FrameComparison
  {
    double                time;
    double                hausdorff;
    double                centroid_distance;
    std::optional<double> energy_a, energy_b; // from log.csv; none at t = 0 or without a log
  };

  struct RunComparison
  {
    std::vector<FrameComparison> frames;

    double mean_hausdorff() const;
    double max_hausdorff() const;
    double mean_centroid_distance() const;
  };

  // Each frame of run A is paired with the frame of run B at the same time (same_time());
  // frames without a partner are skipped. Throws InputError naming the file when a run folder,
  // its solution.pvd or a VTU file is missing or invalid, or when no frame times are shared.
  RunComparison compare_runs(const std::filesystem::path &run_a, const std::filesystem::path &run_b);

  // {"frames", "mean_hausdorff", "max_hausdorff", "per_frame": [{"time", "hausdorff",
  // "energy_a", "energy_b", "centroid_distance"}], "centroid_distance_mean"}; unknown values
  // are null.
  void write_json(std::ostream &out, const RunComparison &comparison);
} // namespace ritr::compare
