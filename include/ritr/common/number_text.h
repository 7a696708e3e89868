#pragma once
// A number as messages print it: the stream's shortest default form ("0.05", "1e+50").
#include <string>

namespace ritr
{
  std::string number_text(double value);
} // namespace ritr
