// `pdd quality MESH [--json]`: triangle quality and surface checks of any
// triangle mesh, to compare pdd's output with other tools'.
#include <pdd/io.h>
#include <pdd/report.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.h"

namespace pdd::cli {
namespace {

struct QualityArgs {
  std::string mesh;
  bool json = false;
};

}  // namespace

void add_quality_command(CLI::App& app) {
  auto args = std::make_shared<QualityArgs>();
  CLI::App* cmd =
      app.add_subcommand("quality",
                         "Triangle quality and surface checks (manifold, closed, components, Euler "
                         "characteristic, genus) of a triangle mesh (.ply, .off, .obj)");
  cmd->add_option("MESH", args->mesh, "Triangle mesh to measure")->required();
  cmd->add_flag("--json", args->json, "Print JSON instead of text");
  cmd->callback([args] {
    const TriangleMesh mesh = read_mesh(args->mesh);
    std::cout << quality_report(args->mesh, mesh, args->json);
  });
}

}  // namespace pdd::cli
