#include <ritr/common/number_text.h>

#include <sstream>

namespace ritr
{
  std::string number_text(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }
} // namespace ritr
