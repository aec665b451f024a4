#include "commands.h"
namespace pdd::cli {
void add_quality_command(CLI::App& app) { app.add_subcommand("quality", "Mesh quality"); }
}
