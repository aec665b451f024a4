// Typed exceptions for what a user can cause. Messages name the file, the
// line or the value at fault; the command line prints them on one line.
#pragma once

#include <stdexcept>
#include <string>

namespace pdd {

// Bad input: unreadable or malformed file, degenerate point set, bad option.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A numerical solver that did not converge or could not factorize.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pdd
