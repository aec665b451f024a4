// The options of a reconstruction by name, as the command line (--target-edge)
// and the Python module (target_edge=) spell them: one table, so that both
// clients expose the same options with the same defaults, bounds and messages.
#pragma once

#include <pdd/pipeline.h>

#include <functional>
#include <string>
#include <vector>

namespace pdd {

struct OptionSpec {
  enum class Kind {
    kChoice,   // one of `choices`
    kNumber,   // a finite double within the bounds
    kInteger,  // an integer within the bounds
    kSeed,     // an unsigned 64-bit integer
    kSize,     // a memory size such as 8G (parse_memory_size)
    kFlag,     // true or false
    kText,     // free text, checked by `set`
  };
  std::string name;  // without dashes, words joined by '-': "target-edge"
  Kind kind = Kind::kNumber;
  std::string help;
  std::vector<std::string> choices;  // kChoice
  std::string default_text;          // "" when the default is derived from the input
  // Parses `value` and stores it in `options`; InputError
  // "--name: must be ..., got 'value'" when it is not a valid value.
  std::function<void(ReconstructOptions& options, const std::string& value)> set;
};

// Every option of `pdd reconstruct` that shapes the run (not the output
// files), in the order of `pdd reconstruct --help`.
const std::vector<OptionSpec>& reconstruct_option_specs();

// Sets the option `name` ("target-edge" or "target_edge") from its text;
// InputError for an unknown name or a bad value.
void set_reconstruct_option(ReconstructOptions& options, const std::string& name,
                            const std::string& value);

}  // namespace pdd
