#include <ritr/common/input_error.h>
#include <ritr/compare/energy_log.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace ritr::compare
{
  namespace
  {
    std::vector<std::string> split_csv_line(const std::string &line)
    {
      std::vector<std::string> fields;
      std::istringstream       in(line);
      for (std::string field; std::getline(in, field, ',');)
        {
          field.erase(std::remove_if(field.begin(), field.end(), [](char c) { return c == '\r' || c == ' '; }),
                      field.end());
          fields.push_back(field);
        }
      return fields;
    }
  } // namespace

  bool same_time(const double a, const double b)
  {
    return std::abs(a - b) <= 1e-5 * std::max(std::abs(a), std::abs(b));
  }

  EnergyLog::EnergyLog(const std::filesystem::path &csv_file)
  {
    std::ifstream in(csv_file);
    if (!in)
      return;
    const auto fail = [&](const std::string &what) { throw InputError(csv_file.string() + ": " + what); };

    std::string header;
    std::getline(in, header);
    const std::vector<std::string> columns = split_csv_line(header);
    const auto column = [&](const std::string &name) {
      const auto it = std::find(columns.begin(), columns.end(), name);
      if (it == columns.end())
        fail("no '" + name + "' column in the header");
      return static_cast<std::size_t>(it - columns.begin());
    };
    const std::size_t time_column = column("time"), energy_column = column("energy");

    unsigned int line_number = 1;
    for (std::string line; std::getline(in, line);)
      {
        ++line_number;
        if (line.empty() || line == "\r")
          continue;
        const std::vector<std::string> fields = split_csv_line(line);
        try
          {
            std::size_t used_time = 0, used_energy = 0;
            const double time   = std::stod(fields.at(time_column), &used_time);
            const double energy = std::stod(fields.at(energy_column), &used_energy);
            if (used_time != fields[time_column].size() || used_energy != fields[energy_column].size())
              throw std::invalid_argument("trailing characters");
            rows_.emplace_back(time, energy);
          }
        catch (const std::logic_error &)
          {
            fail("line " + std::to_string(line_number) + ": malformed time or energy");
          }
      }
  }

  std::optional<double> EnergyLog::energy_at(const double time) const
  {
    for (const auto &[t, energy] : rows_)
      if (same_time(t, time))
        return energy;
    return std::nullopt;
  }
} // namespace ritr::compare
