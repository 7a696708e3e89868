#include <ritr/output/run_directory.h>
#include <ritr/common/input_error.h>

#include <unistd.h>

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <vector>

namespace ritr
{
  namespace fs = std::filesystem;

  namespace
  {
    bool ends_with(const std::string &s, const std::string &end)
    {
      return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
    }

    // The digits of STEM-NNNNN.EXT (one or more), or "" when `name` is not of that form.
    std::string number_of(const std::string &name, const std::string &stem, const std::string &extension)
    {
      const std::size_t first = stem.size() + 1;
      if (name.size() <= first + extension.size() || name.compare(0, first, stem + "-") != 0 ||
          !ends_with(name, extension))
        return "";
      const auto digits = name.substr(first, name.size() - first - extension.size());
      const bool all_digits =
        std::all_of(digits.begin(), digits.end(), [](const char c) { return c >= '0' && c <= '9'; });
      return all_digits ? digits : "";
    }

    bool is_numbered(const std::string &name, const std::string &stem, const std::string &extension)
    {
      return !number_of(name, stem, extension).empty();
    }

    // The files written once per frame or step: stem and extension.
    const std::pair<const char *, const char *> numbered_outputs[] = {
      {"solution", ".vtu"}, {"reference", ".vtu"}, {"obstacles", ".vtu"}, {"nodes", ".csv"}};

    std::string quoted(const fs::path &p) { return "'" + shortened(p.string()) + "'"; }

    bool writable(const fs::path &directory) { return access(directory.c_str(), W_OK | X_OK) == 0; }
  } // namespace

  std::string numbered_output(const std::string &stem, const unsigned int n, const std::string &extension)
  {
    std::ostringstream s;
    s << stem << '-' << std::setw(5) << std::setfill('0') << n << extension;
    return s.str();
  }

  bool is_run_output(const std::string &file_name)
  {
    const std::string name = ends_with(file_name, ".tmp") ? file_name.substr(0, file_name.size() - 4) : file_name;
    for (const char *fixed : {"summary.json", "log.csv", "newton.csv", "solution.pvd", "reference.pvd",
                              "obstacles.pvd", "checkpoint.bin"})
      if (name == fixed)
        return true;
    return std::any_of(std::begin(numbered_outputs), std::end(numbered_outputs),
                       [&](const auto &n) { return is_numbered(name, n.first, n.second); });
  }

  std::string output_directory_problem(const fs::path &directory)
  {
    if (directory.empty())
      return "is empty";
    std::error_code      ec;
    const fs::file_status status = fs::status(directory, ec);
    if (status.type() == fs::file_type::not_found)
      {
        // It will be created: its nearest existing ancestor must be a writable directory, and
        // none of the missing folders a symbolic link to nowhere (it cannot be made).
        fs::path ancestor = directory;
        while (fs::status(ancestor, ec).type() == fs::file_type::not_found)
          {
            if (fs::symlink_status(ancestor, ec).type() == fs::file_type::symlink)
              return "cannot be created: " + quoted(ancestor) + " is a symbolic link to a missing target";
            if (ancestor == ".")
              break;
            const bool at_top = !ancestor.has_parent_path() || ancestor.parent_path() == ancestor;
            ancestor          = at_top ? fs::path(".") : ancestor.parent_path();
          }
        if (!fs::is_directory(ancestor, ec))
          return "cannot be created: " + quoted(ancestor) + " is not a directory";
        if (!writable(ancestor))
          return "cannot be created: " + quoted(ancestor) + " is not writable";
        return "";
      }
    if (ec)
      return "cannot be used: " + ec.message();
    if (!fs::is_directory(status))
      return "exists and is not a directory";
    if (!writable(directory))
      return "is not writable";
    // A run replaces its outputs by renaming temporaries: no directory may stand in the way.
    for (const auto &entry : fs::directory_iterator(directory, ec))
      if (is_run_output(entry.path().filename().string()) && !entry.is_regular_file(ec))
        return "holds " + quoted(entry.path().filename()) + ", which is not a file but has an output's name";
    if (ec)
      return "cannot be listed: " + ec.message();
    return "";
  }

  void remove_previous_outputs(const fs::path &directory)
  {
    std::vector<fs::path> checkpoints, collections, others;
    for (const auto &entry : fs::directory_iterator(directory))
      {
        const std::string name = entry.path().filename().string();
        if (!is_run_output(name) || name == "summary.json")
          continue;
        (name == "checkpoint.bin" ? checkpoints : ends_with(name, ".pvd") ? collections : others)
          .push_back(entry.path());
      }
    for (const auto *files : {&checkpoints, &collections, &others})
      for (const auto &file : *files)
        fs::remove(file);
  }

  void remove_outputs_after(const fs::path &directory, const unsigned int step)
  {
    std::vector<fs::path> later;
    for (const auto &entry : fs::directory_iterator(directory))
      {
        const std::string name = entry.path().filename().string();
        if (!is_run_output(name))
          continue;
        if (ends_with(name, ".tmp"))
          later.push_back(entry.path());
        else
          for (const auto &[stem, extension] : numbered_outputs)
            {
              const std::string digits = number_of(name, stem, extension);
              if (digits.empty())
                continue;
              const std::size_t first = std::min(digits.find_first_not_of('0'), digits.size() - 1);
              // More digits than any step count has: later than every step.
              if (digits.size() - first > 10 || std::stoull(digits.substr(first)) > step)
                later.push_back(entry.path());
            }
      }
    for (const auto &file : later)
      fs::remove(file);
  }
} // namespace ritr
