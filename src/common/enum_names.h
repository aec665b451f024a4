// Names of an enum's values, as options and statistics spell them: one table
// per enum gives both its parse function (any case; InputError listing the
// names otherwise) and its to_string.
#pragma once

#include <pdd/errors.h>

#include <cctype>
#include <string>
#include <utility>

#include "common/quote.h"

namespace pdd {

template <typename Enum>
using EnumNames = std::pair<Enum, const char*>;

template <typename Enum, std::size_t N>
Enum parse_enum(const std::string& text, const EnumNames<Enum> (&names)[N],
                const std::string& what) {
  std::string lower = text;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string known;
  for (const auto& [value, name] : names) {
    if (lower == name) return value;
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  throw InputError("unknown " + what + " " + quote(text) + " (" + known + ")");
}

template <typename Enum, std::size_t N>
std::string enum_name(Enum value, const EnumNames<Enum> (&names)[N]) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "unknown";
}

}  // namespace pdd
