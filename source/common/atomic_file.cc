#include <ritr/common/atomic_file.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace ritr
{
  void write_file_atomically(const std::string &path, const std::function<void(std::ostream &)> &write)
  {
    const std::string temporary = path + ".tmp";
    {
      std::ofstream out(temporary, std::ios::binary);
      if (!out)
        throw std::runtime_error("cannot write '" + path + "'");
      out.precision(17);
      write(out);
      out.flush();
      if (!out)
        throw std::runtime_error("error while writing '" + path + "'");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
      throw std::runtime_error("cannot rename '" + temporary + "' to '" + path + "'");
  }
} // namespace ritr
