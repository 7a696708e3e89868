#include <ritr/scene/parameter_text.h>

#include <charconv>
#include <cstdlib>
#include <stdexcept>

namespace ritr
{
  std::string prm_value(const double value)
  {
    if (value == 0)
      return "0";
    char       buffer[64];
    const auto format = [&](const std::chars_format style) {
      const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value, style);
      if (error != std::errc())
        throw std::logic_error("prm_value: cannot format a double");
      return std::string(buffer, end);
    };
    // Shortest round-trip digits, "d.ddde-XX".
    const std::string scientific = format(std::chars_format::scientific);
    const auto        e          = scientific.find('e');
    const int         exponent   = std::atoi(scientific.c_str() + e + 1);
    if (exponent >= -2 && exponent <= 3)
      return format(std::chars_format::fixed);
    return scientific.substr(0, e + 1) + std::to_string(exponent);
  }

  std::string prm_value(const int value) { return std::to_string(value); }

  std::string prm_value(const unsigned int value) { return std::to_string(value); }

  std::string prm_value(const bool value) { return value ? "true" : "false"; }

  namespace
  {
    template <typename Number>
    std::string comma_separated(const std::vector<Number> &values)
    {
      std::string text;
      for (const Number v : values)
        text += (text.empty() ? "" : ",") + prm_value(v);
      return text;
    }
  } // namespace

  std::string prm_value(const std::vector<double> &values) { return comma_separated(values); }

  std::string prm_value(const std::vector<unsigned int> &values) { return comma_separated(values); }
} // namespace ritr
