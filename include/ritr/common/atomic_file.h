#pragma once
// Writes a file under a temporary name and renames it into place, so that a run killed
// mid-write never leaves a torn output file (and never clobbers the previous version).
#include <functional>
#include <ostream>
#include <string>

namespace ritr
{
  // Calls `write` on a stream to `path + ".tmp"`, then renames it to `path`. Throws
  // std::runtime_error naming the file when it cannot be written.
  void write_file_atomically(const std::string &path, const std::function<void(std::ostream &)> &write);
} // namespace ritr
