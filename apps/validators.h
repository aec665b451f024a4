// Number validators for the command line whose messages state the bound
// (CLI11's NonNegativeNumber and PositiveNumber print the range up to the
// largest double).
#pragma once

#include <CLI/CLI.hpp>

#include <sstream>
#include <string>

namespace pdd::cli {

// Accepts numbers x with x > bound, or x >= bound when `inclusive`.
inline CLI::Validator number_bound(double bound, bool inclusive) {
  std::ostringstream text;
  text << bound;
  const std::string limit = text.str();
  const std::string relation = inclusive ? ">=" : ">";
  return CLI::Validator(
      [bound, inclusive, limit, relation](std::string& value) -> std::string {
        std::istringstream in(value);
        double number = 0;
        if (in >> number && in.eof() && (inclusive ? number >= bound : number > bound)) return "";
        return "must be a number " + relation + " " + limit + ", got '" + value + "'";
      },
      "NUMBER" + relation + limit);
}

inline CLI::Validator greater_than(double bound) { return number_bound(bound, false); }
inline CLI::Validator at_least(double bound) { return number_bound(bound, true); }

}  // namespace pdd::cli
