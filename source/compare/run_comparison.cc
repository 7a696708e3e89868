#include <ritr/common/input_error.h>
#include <ritr/compare/boundary.h>
#include <ritr/compare/energy_log.h>
#include <ritr/compare/hausdorff.h>
#include <ritr/compare/run_comparison.h>
#include <ritr/compare/vtk_reader.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

namespace ritr::compare
{
  namespace
  {
    std::vector<PvdFrame> read_series(const std::filesystem::path &run)
    {
      if (!std::filesystem::is_directory(run))
        throw InputError(run.string() + ": no such run directory");
      return read_pvd(run / "solution.pvd");
    }

    // JSON has no NaN or infinity: unknown or non-finite values are written as null.
    void write_number(std::ostream &out, const std::optional<double> &value)
    {
      if (value && std::isfinite(*value))
        out << *value;
      else
        out << "null";
    }

    template <typename Member>
    double mean_of(const std::vector<FrameComparison> &frames, const Member member)
    {
      double sum = 0.0;
      for (const auto &f : frames)
        sum += f.*member;
      return frames.empty() ? 0.0 : sum / frames.size();
    }
  } // namespace

  double RunComparison::mean_hausdorff() const
  {
    return mean_of(frames, &FrameComparison::hausdorff);
  }

  double RunComparison::max_hausdorff() const
  {
    double m = 0.0;
    for (const auto &f : frames)
      m = std::max(m, f.hausdorff);
    return m;
  }

  double RunComparison::mean_centroid_distance() const
  {
    return mean_of(frames, &FrameComparison::centroid_distance);
  }

  RunComparison compare_runs(const std::filesystem::path &run_a, const std::filesystem::path &run_b)
  {
    const std::vector<PvdFrame> frames_a = read_series(run_a), frames_b = read_series(run_b);
    const EnergyLog             log_a(run_a / "log.csv"), log_b(run_b / "log.csv");

    RunComparison comparison;
    for (const PvdFrame &a : frames_a)
      {
        const auto b = std::min_element(frames_b.begin(), frames_b.end(), [&](const PvdFrame &p, const PvdFrame &q) {
          return std::abs(p.time - a.time) < std::abs(q.time - a.time);
        });
        if (b == frames_b.end() || !same_time(a.time, b->time))
          continue;
        const DeformedMesh mesh_a = read_deformed_mesh(a.file), mesh_b = read_deformed_mesh(b->file);
        if (mesh_a.dim != mesh_b.dim)
          throw InputError(b->file.string() + ": a " + std::to_string(mesh_b.dim) + "D mesh, but " +
                           a.file.string() + " is " + std::to_string(mesh_a.dim) + "D");
        comparison.frames.push_back({a.time, hausdorff_distance(extract_boundary(mesh_a), extract_boundary(mesh_b)),
                                     distance(centroid(mesh_a), centroid(mesh_b)), log_a.energy_at(a.time),
                                     log_b.energy_at(a.time)});
      }
    if (comparison.frames.empty())
      throw InputError((run_a / "solution.pvd").string() + " and " + (run_b / "solution.pvd").string() +
                       ": no frame times in common");
    return comparison;
  }

  void write_json(std::ostream &out, const RunComparison &comparison)
  {
    const auto precision = out.precision(12);
    out << "{\"frames\": " << comparison.frames.size() << ", \"mean_hausdorff\": " << comparison.mean_hausdorff()
        << ", \"max_hausdorff\": " << comparison.max_hausdorff() << ", \"per_frame\": [";
    for (std::size_t i = 0; i < comparison.frames.size(); ++i)
      {
        const FrameComparison &f = comparison.frames[i];
        out << (i ? ", " : "") << "{\"time\": " << f.time << ", \"hausdorff\": " << f.hausdorff << ", \"energy_a\": ";
        write_number(out, f.energy_a);
        out << ", \"energy_b\": ";
        write_number(out, f.energy_b);
        out << ", \"centroid_distance\": " << f.centroid_distance << "}";
      }
    out << "], \"centroid_distance_mean\": " << comparison.mean_centroid_distance() << "}\n";
    out.precision(precision);
  }
} // namespace ritr::compare
