#pragma once
// Runs the ritr executable (test_paths.h), in the foreground capturing its exit code and
// output, or in the background; reads and writes whole files and folders.
#include "test_paths.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace ritr::test_support
{
  struct RunResult
  {
    int         exit_code = -1;
    std::string output;  // stdout and stderr together
  };

  // A small valid 2D scene: a strip above a ground plane, two steps. "OUTPUT" stands for its
  // output directory.
  inline const std::string small_scene = R"(set dimension = 2
set time step = 0.01
set end time = 0.02
set output directory = OUTPUT
subsection Body 0
  set shape = rectangle
  set upper = 1, 0.2
  set subdivisions = 4, 1
  set translation = 0, 0.01
end
subsection Obstacle 0
  set type = plane
  set point = 0, 0
end
subsection Contact
  set dhat = 1e-3
end
)";

  // `text` with its first `from` replaced by `to`.
  inline std::string replaced(std::string text, const std::string &from, const std::string &to)
  {
    return text.replace(text.find(from), from.size(), to);
  }

  // Runs a shell command line; `redirections` says where the streams go ("2>&1": both are
  // captured).
  inline RunResult run_command(const std::string &command_line, const std::string &redirections = "2>&1")
  {
    const std::string command = command_line + " " + redirections;
    RunResult         r;
    FILE             *pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buffer;
    while (fgets(buffer.data(), buffer.size(), pipe))
      r.output += buffer.data();
    const int status = pclose(pipe);
    r.exit_code      = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
  }

  inline RunResult run_ritr(const std::string &arguments, const std::string &redirections = "2>&1")
  {
    return run_command(ritr_binary() + " " + arguments, redirections);
  }

  // Starts ritr with `arguments` in the background, its output discarded; returns its process
  // id (for waitpid and kill).
  inline pid_t start_ritr(const std::vector<std::string> &arguments)
  {
    // Everything the child needs is made before fork: it only calls exec.
    const std::string   binary = ritr_binary();
    std::vector<char *> argv{const_cast<char *>("ritr")};
    for (const auto &a : arguments)
      argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0)
      {
        const int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        dup2(null, 2);
        execv(binary.c_str(), argv.data());
        _exit(127);
      }
    return pid;
  }

  // The exit code of a process started by start_ritr, once it has ended (-1: killed).
  inline int exit_code_of(const pid_t pid)
  {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  inline std::string read_file(const std::string &path)
  {
    std::ifstream     in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  inline void write_file(const std::string &path, const std::string &text)
  {
    std::ofstream(path, std::ios::binary) << text;
  }

  // A CSV file of ritr's (log.csv, newton.csv): a header of column names, and rows both as
  // numbers (a text or empty cell reads NaN) and as the text of each cell.
  struct CsvTable
  {
    std::vector<std::string>              header;
    std::vector<std::vector<double>>      rows;
    std::vector<std::vector<std::string>> text;

    // Index of the named column (header.size() when there is none).
    std::size_t column(const std::string &name) const
    {
      return std::find(header.begin(), header.end(), name) - header.begin();
    }
  };

  inline CsvTable read_csv(const std::string &path)
  {
    CsvTable           table;
    std::istringstream in(read_file(path));
    std::string        line;
    for (bool first = true; std::getline(in, line); first = false)
      {
        // Split on every comma, so that a trailing empty cell is a cell too.
        std::vector<std::string> cells{""};
        for (const char c : line)
          if (c == ',')
            cells.emplace_back();
          else
            cells.back().push_back(c);
        if (first)
          {
            table.header = cells;
            continue;
          }
        table.text.push_back(cells);
        table.rows.emplace_back();
        for (const auto &cell : cells)
          {
            char        *end   = nullptr;
            const double value = std::strtod(cell.c_str(), &end);
            table.rows.back().push_back(!cell.empty() && *end == '\0' ? value : std::nan(""));
          }
      }
    return table;
  }

  // The named column of a CSV file of ritr's, as numbers.
  inline std::vector<double> csv_column(const std::string &path, const std::string &name)
  {
    const CsvTable      t = read_csv(path);
    std::vector<double> c;
    for (const auto &row : t.rows)
      c.push_back(row[t.column(name)]);
    return c;
  }


  // Writes NAME.prm: the scene prm/verification/NAME.prm with its output directory set to
  // `directory` and `extra` (whole subsections) appended. Returns the file's name.
  inline std::string scene_variant(const std::string &name, const std::string &variant,
                                   const std::string &directory, const std::string &extra)
  {
    std::string       text = read_file(source_dir() + "/prm/verification/" + name + ".prm");
    const std::size_t at   = text.find("set output directory");
    text.replace(at, text.find('\n', at) - at, "set output directory = " + directory);
    const std::string file = name + "-" + variant + ".prm";
    write_file(file, text + extra);
    return file;
  }

  // Every file and folder under `folder`, with the files' contents, to compare byte for byte.
  inline std::map<std::string, std::string> snapshot(const std::string &folder)
  {
    std::map<std::string, std::string> files;
    for (const auto &entry : std::filesystem::recursive_directory_iterator(folder))
      files[entry.path().string()] = entry.is_directory() ? "(folder)" : read_file(entry.path().string());
    return files;
  }
} // namespace ritr::test_support
