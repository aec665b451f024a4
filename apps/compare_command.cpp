// `pdd compare A B [--json]`: Metro-style two-sided distances between two
// triangle meshes (Table 1 of §4.2), B being the reference (ground truth).
#include <pdd/compare.h>
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/report.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <new>
#include <stdexcept>
#include <sstream>
#include <string>

#include "commands.h"
#include "validators.h"

namespace pdd::cli {
namespace {

struct CompareArgs {
  std::string a;  // the mesh to measure
  std::string b;  // the reference mesh
  CompareOptions options;
  bool json = false;
};

// Reads a mesh and rejects one without area, naming the file.
TriangleMesh read_surface(const std::string& path) {
  TriangleMesh mesh = read_mesh(path);
  require_area(mesh, path);
  return mesh;
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Two-sided distances between two triangle meshes (.ply, .off, .obj) by area-uniform "
      "sampling: Hausdorff, mean, RMS, Chamfer-L1, F-score; B is the reference");
  cmd->add_option("A", args->a, "Mesh to measure")->required();
  cmd->add_option("B", args->b, "Reference mesh (relative values use its bounding-box diagonal)")
      ->required();
  cmd->add_flag("--json", args->json, "Print a JSON object instead of text");
  cmd->add_option("--samples", args->options.samples,
                  "Samples on each surface (about 70 bytes each while it runs)")
      ->check(CLI::Range(std::size_t{1}, CompareOptions::kMaxSamples))
      ->capture_default_str();
  cmd->add_option("--fscore-threshold", args->options.fscore_threshold,
                  "F-score threshold τ, as a fraction of B's bounding-box diagonal")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed of the sampling")->capture_default_str();
  cmd->callback([args] {
    const TriangleMesh a = read_surface(args->a);
    const TriangleMesh b = read_surface(args->b);
    SurfaceDistance d;
    try {
      d = compare_surfaces(a, b, args->options);
    } catch (const std::bad_alloc&) {
      throw std::runtime_error("compare: not enough memory for " +
                               std::to_string(args->options.samples) +
                               " samples on each surface (about 70 bytes each); use fewer "
                               "(--samples)");
    }
    std::cout << comparison_report(args->a, args->b, args->options, d, args->json);
  });
}

}  // namespace pdd::cli
