#include <ritr/output/directory_lock.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

namespace ritr
{
  namespace
  {
    std::string system_error(const std::string &what) { return what + ": " + std::strerror(errno); }

    // The process id the owner wrote into the lock file. The owner writes it right after it
    // takes the lock, so an empty file is read again for a moment.
    std::string owner_of(const int descriptor)
    {
      for (int attempt = 0; attempt < 100; ++attempt)
        {
          char          text[32] = {};
          const ssize_t n        = pread(descriptor, text, sizeof(text) - 1, 0);
          std::string   pid(text, n > 0 ? n : 0);
          while (!pid.empty() && (pid.back() == '\n' || pid.back() == '\0'))
            pid.pop_back();
          if (!pid.empty() && pid.find_first_not_of("0123456789") == std::string::npos)
            return pid;
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      return "";
    }

    // Whether `descriptor` is still the file at `path`: a previous owner removes the file
    // before it releases its lock, and a lock on a removed file protects nothing.
    bool still_at(const int descriptor, const std::filesystem::path &path)
    {
      struct stat opened, named;
      return fstat(descriptor, &opened) == 0 && stat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
             opened.st_ino == named.st_ino;
    }
  } // namespace

  OutputDirectoryLock::OutputDirectoryLock(const std::filesystem::path &directory)
    : file_(directory / file_name)
  {
    while (true)
      {
        descriptor_ = open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (descriptor_ < 0)
          throw std::runtime_error(system_error("cannot hold its lock file " + std::string(file_name)));
        if (flock(descriptor_, LOCK_EX | LOCK_NB) != 0)
          {
            const int         error = errno;
            const std::string owner = error == EWOULDBLOCK ? owner_of(descriptor_) : "";
            close(descriptor_);
            errno = error;
            if (error != EWOULDBLOCK)
              throw std::runtime_error(system_error("cannot be locked"));
            throw std::runtime_error("is in use by another ritr run" +
                                     (owner.empty() ? std::string() : " (process " + owner + ")"));
          }
        if (still_at(descriptor_, file_))
          break;
        close(descriptor_);
      }
    const std::string pid = std::to_string(getpid()) + "\n";
    if (ftruncate(descriptor_, 0) != 0 || pwrite(descriptor_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
      {
        const std::string error = system_error("cannot write its lock file " + std::string(file_name));
        unlink(file_.c_str());
        close(descriptor_);
        throw std::runtime_error(error);
      }
  }

  OutputDirectoryLock::~OutputDirectoryLock()
  {
    // Removed while still locked: a run that opened the file meanwhile sees that it is gone
    // (still_at) and makes a new one.
    unlink(file_.c_str());
    close(descriptor_);
  }
} // namespace ritr
