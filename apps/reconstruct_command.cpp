#include "commands.h"
namespace pdd::cli {
void add_reconstruct_command(CLI::App& app) { app.add_subcommand("reconstruct", "Reconstruct a surface"); }
}
