// A value from a file or an option as it goes into an error message: in
// single quotes, non-printable bytes (and the quote and backslash) escaped as
// \xNN, long values shortened, so that a message stays one readable line
// whatever bytes the input holds (a NUL, terminal escapes, a 1 MB token).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace pdd {

inline std::string quote(std::string_view value, std::size_t max_length = 40) {
  std::string out = "'";
  for (std::size_t i = 0; i < value.size() && i < max_length; ++i) {
    const unsigned char c = static_cast<unsigned char>(value[i]);
    if (c < 0x20 || c >= 0x7f || c == '\'' || c == '\\') {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (value.size() > max_length) out += "...";
  return out + "'";
}

}  // namespace pdd
