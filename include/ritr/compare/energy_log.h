#pragma once
// The energy column of a run's log.csv, looked up by time.
#include <filesystem>
#include <optional>
#include <vector>

namespace ritr::compare
{
  // Whether two output times denote the same instant. Times are printed with six significant
  // digits, so allow a relative difference of 1e-5 (more than the printing error, far less than
  // any time step of a run).
  bool same_time(double a, double b);

  class EnergyLog
  {
  public:
    // Reads the "time" and "energy" columns, found by header name. A missing file gives an
    // empty log (every energy unknown); a file without those columns or with a malformed number
    // throws InputError naming it.
    explicit EnergyLog(const std::filesystem::path &csv_file);

    // The energy logged at `time`, if a row has that time.
    std::optional<double> energy_at(double time) const;

  private:
    std::vector<std::pair<double, double>> rows_; // (time, energy)
  };
} // namespace ritr::compare
