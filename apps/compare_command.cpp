// `pdd compare A B [--json]`: Metro-style two-sided distances between two
// triangle meshes (Table 1 of §4.2), B being the reference (ground truth).
#include <pdd/compare.h>
#include <pdd/errors.h>
#include <pdd/io.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.h"
#include "json.h"
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
  if (!(surface_area(mesh) > 0))
    throw InputError(path + ": the mesh has no area (all " + std::to_string(mesh.faces.size()) +
                     " faces are degenerate)");
  return mesh;
}

std::string json(const CompareArgs& args, const SurfaceDistance& d) {
  std::ostringstream o;
  auto value = [&o](const std::string& key, const std::string& v, bool last = false) {
    o << "  " << json_string(key) << ": " << v << (last ? "\n" : ",\n");
  };
  // A distance, then the same relative to B's diagonal.
  auto distance = [&](const std::string& key, double v) {
    value(key, significant(v, 9));
    value(key + "_relative", significant(d.relative(v), 9));
  };
  o << "{\n";
  value("a", json_string(args.a));
  value("b", json_string(args.b));
  value("samples", std::to_string(args.options.samples));
  value("seed", std::to_string(args.options.seed));
  value("relative_to", json_string("bounding-box diagonal of b"));
  value("diagonal_b", significant(d.diagonal, 9));
  distance("hausdorff", d.hausdorff);
  distance("chamfer_l1", d.chamfer_l1);
  distance("mean_a_to_b", d.a_to_b.mean);
  distance("mean_b_to_a", d.b_to_a.mean);
  distance("rms_a_to_b", d.a_to_b.rms);
  distance("rms_b_to_a", d.b_to_a.rms);
  distance("max_a_to_b", d.a_to_b.max);
  distance("max_b_to_a", d.b_to_a.max);
  distance("fscore_threshold", d.threshold);
  value("precision", significant(d.precision, 9));
  value("recall", significant(d.recall, 9));
  value("fscore", significant(d.fscore, 9), true);
  o << "}\n";
  return o.str();
}

std::string text(const CompareArgs& args, const SurfaceDistance& d) {
  std::ostringstream o;
  auto row = [&o, &d](const char* name, double v) {
    char line[128];
    std::snprintf(line, sizeof line, "  %-12s %14s %12s %%\n", name, significant(v, 6).c_str(),
                  number(100 * d.relative(v), 4).c_str());
    o << line;
  };
  o << "A: " << args.a << "\n"
    << "B: " << args.b << " (reference)\n"
    << args.options.samples << " area-uniform samples on each surface (seed " << args.options.seed
    << "); relative to B's bounding-box diagonal " << significant(d.diagonal, 6) << "\n"
    << "                     distance     relative\n";
  row("Hausdorff", d.hausdorff);
  row("Chamfer-L1", d.chamfer_l1);
  row("mean A->B", d.a_to_b.mean);
  row("mean B->A", d.b_to_a.mean);
  row("RMS A->B", d.a_to_b.rms);
  row("RMS B->A", d.b_to_a.rms);
  row("max A->B", d.a_to_b.max);
  row("max B->A", d.b_to_a.max);
  o << "F-score at " << number(100 * args.options.fscore_threshold, 3) << " % of the diagonal ("
    << significant(d.threshold, 6) << "): " << number(d.fscore, 4) << "  (precision "
    << number(d.precision, 4) << ", recall " << number(d.recall, 4) << ")\n";
  return o.str();
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
  cmd->add_option("--samples", args->options.samples, "Samples on each surface")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40))
      ->capture_default_str();
  cmd->add_option("--fscore-threshold", args->options.fscore_threshold,
                  "F-score threshold τ, as a fraction of B's bounding-box diagonal")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed of the sampling")->capture_default_str();
  cmd->callback([args] {
    const TriangleMesh a = read_surface(args->a);
    const TriangleMesh b = read_surface(args->b);
    const SurfaceDistance d = compare_surfaces(a, b, args->options);
    std::cout << (args->json ? json(*args, d) : text(*args, d));
  });
}

}  // namespace pdd::cli
