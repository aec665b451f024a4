// The library's option table (options.h) on a subcommand: each option named
// as the table names it, its help and default shown, its value parsed by the
// table after CLI11 has read the command line.
#pragma once

#include <CLI/CLI.hpp>

#include <pdd/options.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace pdd::cli {

using OptionValues = std::map<std::string, std::string>;  // the options given, by name

// Adds the options of the table for which `wanted(name)` holds; the values the
// user gives land in `values`. Apply them with apply_table_options.
void add_table_options(CLI::App* cmd, const std::shared_ptr<OptionValues>& values,
                       const std::function<bool(const std::string&)>& wanted);

// Sets every given option on `options` (InputError naming the option when a
// value is bad).
void apply_table_options(const OptionValues& values, ReconstructOptions& options);

}  // namespace pdd::cli
