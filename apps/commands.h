// The subcommands of the `pdd` command line. Each file apps/<name>_command.cpp
// adds one subcommand whose callback does the work by calling the library.
// Callbacks report user errors by throwing pdd::InputError (exit code 2) and
// other failures by throwing any std::exception (exit code 1).
#pragma once

#include <CLI/CLI.hpp>

namespace pdd::cli {

void add_reconstruct_command(CLI::App& app);
void add_quality_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_normals_command(CLI::App& app);

}  // namespace pdd::cli
