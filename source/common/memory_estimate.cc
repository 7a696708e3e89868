#include <ritr/common/memory_estimate.h>

#include <unistd.h>

#include <sstream>

namespace ritr
{
  double physical_memory_bytes()
  {
    return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  }

  std::string memory_problem(const double count, const double bytes_each, const std::string &items)
  {
    const double needed = count * bytes_each, available = physical_memory_bytes();
    if (needed <= available)
      return "";
    std::ostringstream s;
    s.precision(2);
    s << "make " << count << ' ' << items << ", which need at least " << needed
      << " bytes of memory (this machine has " << available << ")";
    return s.str();
  }
} // namespace ritr
