#pragma once
// Bad input and the words that report it: one printable line however hostile the input.
// Shared by ritr and ritr-compare; both map it to exit code 2 with its message as the single
// line on stderr.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace ritr
{
  // Bad input: the message names the file, the entry and what is wrong. Control bytes and
  // invalid UTF-8 are escaped (\xNN) so that the message stays one printable line.
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message);
  };

  // A bad value of one entry of a parameter file ("Contact/dhat"), thrown where the file's
  // name and lines are not known: its reader reports it as an InputError that names them.
  class EntryError : public std::invalid_argument
  {
  public:
    EntryError(const std::string &entry, const std::string &what)
      : std::invalid_argument(what)
      , entry(entry)
    {}
    std::string entry;
  };

  // Input echoed in a message (a value, a path): escaped as above and, when longer than
  // `max_length`, cut to its start with the full length noted.
  std::string shortened(const std::string &text, std::size_t max_length = 80);
} // namespace ritr
