#pragma once
// The one mapping between an enum's values and their names in a parameter file, both ways:
// a table of (value, name) pairs in the order the documentation lists them.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace ritr
{
  template <typename Enum, std::size_t n>
  using EnumNames = std::array<std::pair<Enum, const char *>, n>;

  // The value named `name`; throws std::invalid_argument("unknown WHAT 'NAME'") for any other.
  template <typename Enum, std::size_t n>
  Enum value_named(const EnumNames<Enum, n> &names, const std::string &name, const std::string &what)
  {
    for (const auto &[value, text] : names)
      if (name == text)
        return value;
    throw std::invalid_argument("unknown " + what + " '" + name + "'");
  }

  template <typename Enum, std::size_t n>
  std::string name_of(const EnumNames<Enum, n> &names, const Enum value)
  {
    for (const auto &[v, text] : names)
      if (v == value)
        return text;
    throw std::logic_error("enum value without a name");
  }

  // "a|b|c": the pattern of a deal.II Patterns::Selection.
  template <typename Enum, std::size_t n>
  std::string selection(const EnumNames<Enum, n> &names)
  {
    std::string s;
    for (const auto &[value, text] : names)
      s += (s.empty() ? "" : "|") + std::string(text);
    return s;
  }
} // namespace ritr
