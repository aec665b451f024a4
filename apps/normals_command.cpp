// `pdd normals INPUT -o OUTPUT`: the normals a reconstruction would use,
// estimated and oriented (--normals, --orientation), written with the points;
// for other tools that need oriented normals.
#include <pdd/io.h>
#include <pdd/pipeline.h>
#include <pdd/report.h>

#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "table_options.h"

namespace pdd::cli {
namespace {

struct NormalsArgs {
  std::string input;
  std::string output;
  std::shared_ptr<OptionValues> values = std::make_shared<OptionValues>();
  bool ascii = false;
};

}  // namespace

void add_normals_command(CLI::App& app) {
  auto args = std::make_shared<NormalsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "normals",
      "Estimate and orient the normals of a point set as `reconstruct` does first, and write "
      "the points with them (.ply .xyz .pwn .xyzn .off .obj)");
  cmd->add_option("INPUT", args->input, "Point set: .ply .xyz .pwn .xyzn .off .obj")->required();
  cmd->add_option("-o,--output", args->output, "Point set with normals")->required();
  add_table_options(cmd, args->values, [](const std::string& name) {
    return name == "normals" || name == "orientation" || name == "normal-neighbors" ||
           name == "threads" || name == "seed";
  });
  cmd->add_flag("--ascii", args->ascii, "Write a .ply output as ASCII instead of binary");
  cmd->callback([args] {
    ReconstructOptions options;
    apply_table_options(*args->values, options);
    options.source = args->input;
    check_output_path(args->output, OutputKind::kPoints, {args->input});
    ValidationReport report;
    const PointSet points = read_points(args->input, &report);
    for (const std::string& warning : report.warnings)
      std::cerr << "pdd: warning: " << warning << "\n";
    Result result;
    const PointSet with_normals = prepare_normals(points, options, &result.normals);
    write_points(args->output, with_normals, {args->ascii});
    if (const std::string note = normals_note(result); !note.empty())
      std::cerr << "pdd: " << note << "\n";
    std::cout << "pdd: wrote " << args->output << " (" << with_normals.size()
              << " points with normals)\n";
  });
}

}  // namespace pdd::cli
