#include <ritr/common/input_error.h>

#include <cstdio>

namespace ritr
{
  namespace
  {
    // Length of the valid, printable UTF-8 sequence at `i` (0 if there is none): ASCII
    // without control bytes, or a well-formed multi-byte character that is not a C1 control.
    std::size_t printable_sequence(const std::string &s, const std::size_t i)
    {
      const auto byte = [&](const std::size_t k) { return static_cast<unsigned char>(s[k]); };
      const unsigned char lead = byte(i);
      if (lead < 0x80)
        return lead >= 0x20 && lead != 0x7f ? 1 : 0;
      const std::size_t length = lead >= 0xc2 && lead <= 0xdf ? 2 : lead >= 0xe0 && lead <= 0xef ? 3 :
                                 lead >= 0xf0 && lead <= 0xf4 ? 4 : 0;
      if (length == 0 || i + length > s.size() || (lead == 0xc2 && byte(i + 1) < 0xa0))
        return 0;
      for (std::size_t k = 1; k < length; ++k)
        if ((byte(i + k) & 0xc0) != 0x80)
          return 0;
      return length;
    }

    std::string escaped(const std::string &text)
    {
      std::string r;
      for (std::size_t i = 0; i < text.size();)
        if (const std::size_t n = printable_sequence(text, i); n > 0)
          {
            r.append(text, i, n);
            i += n;
          }
        else
          {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(text[i++]));
            r += hex;
          }
      return r;
    }
  } // namespace

  // A message is built from short pieces and shortened values; the cap is a last resort.
  InputError::InputError(const std::string &message)
    : std::runtime_error(shortened(message, 2000))
  {}

  std::string shortened(const std::string &text, const std::size_t max_length)
  {
    if (text.size() <= max_length)
      return escaped(text);
    std::size_t cut = max_length;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80)
      --cut;  // not inside a UTF-8 character
    return escaped(text.substr(0, cut)) + "... (" + std::to_string(text.size()) + " characters)";
  }
} // namespace ritr
