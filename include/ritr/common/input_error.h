#pragma once
// The one exception type for bad input, shared by ritr and ritr-compare; both map it to exit
// code 2 with its message as the single line on stderr.
#include <stdexcept>

namespace ritr
{
  // Bad input: the message names the file, the entry and what is wrong.
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace ritr
