#pragma once
// Runs the ritr executable (path from the RITR_BINARY environment variable that ctest sets)
// and captures its exit code and standard error.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace ritr::test_support
{
  struct RunResult
  {
    int         exit_code = -1;
    std::string output;  // stdout and stderr together
  };

  inline std::string source_dir() { return std::getenv("RITR_SOURCE_DIR"); }

  // Runs a shell command line with stderr joined to stdout.
  inline RunResult run_command(const std::string &command_line)
  {
    const std::string command = command_line + " 2>&1";
    RunResult         r;
    FILE             *pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buffer;
    while (fgets(buffer.data(), buffer.size(), pipe))
      r.output += buffer.data();
    const int status = pclose(pipe);
    r.exit_code      = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
  }

  inline RunResult run_ritr(const std::string &arguments)
  {
    return run_command(std::string(std::getenv("RITR_BINARY")) + " " + arguments);
  }

  inline std::string read_file(const std::string &path)
  {
    std::ifstream     in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  inline void write_file(const std::string &path, const std::string &text)
  {
    std::ofstream(path) << text;
  }
} // namespace ritr::test_support
