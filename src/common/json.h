// Hand-written JSON and text output for the reports (report.h): the numbers and
// strings of a JSON document. A JSON library would be one more dependency for
// a few flat objects.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace pdd {

// v with `digits` digits after the point; "null" when v is not finite (JSON
// has no inf or nan).
inline std::string number(double v, int digits) {
  if (!std::isfinite(v)) return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

// v with `digits` significant digits (for values of any magnitude, e.g.
// distances in the mesh's units); "null" when v is not finite.
inline std::string significant(double v, int digits) {
  if (!std::isfinite(v)) return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

// A JSON string literal (quotes, backslashes and control characters escaped).
inline std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

}  // namespace pdd
