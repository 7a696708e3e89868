#pragma once
// One run per output directory. A run holds an exclusive flock(2) on `ritr.lock` in its
// output directory for as long as it writes there; the file names the owner's process id so
// that a second run can say who holds the directory. The kernel releases the lock of a
// process that dies, so a lock file left by a killed run blocks nobody.
#include <filesystem>

namespace ritr
{
  class OutputDirectoryLock
  {
  public:
    // Takes `directory` (which must exist) for this process. Throws std::runtime_error with
    // a phrase that completes "'DIRECTORY' ..." ("is in use by another ritr run (process
    // 1234)") when another process holds it or the lock file cannot be made.
    explicit OutputDirectoryLock(const std::filesystem::path &directory);
    // Removes the lock file, then releases the lock.
    ~OutputDirectoryLock();

    OutputDirectoryLock(const OutputDirectoryLock &)            = delete;
    OutputDirectoryLock &operator=(const OutputDirectoryLock &) = delete;

    // The name of the lock file in an output directory.
    static constexpr const char *file_name = "ritr.lock";

  private:
    std::filesystem::path file_;
    int                   descriptor_ = -1;
  };
} // namespace ritr
