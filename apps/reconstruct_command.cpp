// `pdd reconstruct INPUT -o OUTPUT [options]`: parse the options, read and
// validate the points, run the progressive pipeline (§3), write the mesh.
#include <pdd/io.h>
#include <pdd/options.h>
#include <pdd/pipeline.h>
#include <pdd/solvers.h>

#include <pdd/report.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "signals.h"
#include "table_options.h"

namespace pdd::cli {

namespace {

// The arguments of `pdd reconstruct`. The pipeline's options carry the
// paper's defaults (§3.2-§3.4); the command line only exposes them.
struct ReconstructArgs {
  std::string input;          // the point set (.ply .xyz .pwn .xyzn .off .obj)
  std::string output;         // the mesh (.ply .off .obj)
  std::string domain_output;  // "" or a .vtu for the final domain with f
  std::string stats_output;   // "" or a .json for the per-iteration statistics
  std::string iterations_dir; // "" or a folder for every iteration's isosurface and domain
  std::shared_ptr<OptionValues> values = std::make_shared<OptionValues>();
  ReconstructOptions options;
  bool ascii = false;  // PLY output as ASCII instead of binary
  bool quiet = false;  // no progress line, no table
};

// The progress callback: stops the run once SIGINT or SIGTERM came, and unless
// `quiet` prints the progress line on stderr: rewritten in place on a terminal, one plain
// line per stage otherwise.
ProgressCallback progress_printer(bool quiet) {
  const bool terminal = ::isatty(STDERR_FILENO);
  return [terminal, quiet, last = Progress{}](const Progress& p) mutable {
    if (cancel_requested()) return false;
    if (quiet) return true;
    // The calls from inside a stage only move the clock on a terminal.
    const bool same_stage = p.stage == last.stage && p.iteration == last.iteration;
    last = p;
    if (same_stage && !terminal) return true;
    char line[160];
    std::snprintf(line, sizeof line, "pdd: %-10s iteration %2d  %9zu vertices  %7.1f s",
                  p.stage.c_str(), p.iteration, p.vertices, p.elapsed_seconds);
    if (terminal) {
      std::cerr << "\r" << line << "\033[K" << std::flush;
    } else {
      std::cerr << line << "\n";
    }
    return true;
  };
}

void reconstruct(ReconstructArgs& args) {
  apply_table_options(*args.values, args.options);
  // Output paths first, so that a typo costs nothing and no output replaces the input.
  const std::vector<std::string> inputs = {args.input};
  check_output_path(args.output, OutputKind::kMesh, inputs);
  if (!args.domain_output.empty())
    check_output_path(args.domain_output, OutputKind::kDomain, inputs);
  if (!args.stats_output.empty())
    check_output_path(args.stats_output, OutputKind::kStatistics, inputs);
  if (!args.iterations_dir.empty()) check_output_path(args.iterations_dir, OutputKind::kFolder);

  ValidationReport report;
  const PointSet points = read_points(args.input, &report);
  for (const std::string& warning : report.warnings) {
    std::cerr << "pdd: warning: " << warning << "\n";
  }
  args.options.source = args.input;

  args.options.progress = progress_printer(args.quiet);
  // All outputs or none, the iterations' too: each is written to a temporary, then all are
  // renamed (unless the run fails or a signal comes: the temporaries then go with `outputs`).
  StagedOutputs outputs;
  on_interrupt([&outputs] { outputs.discard(); });
  struct Forget {
    ~Forget() { on_interrupt({}); }
  } forget;
  if (!args.iterations_dir.empty())
    args.options.on_iteration = iteration_files(args.iterations_dir, args.ascii, &outputs);
  const Result result = pdd::reconstruct(points, args.options);
  if (result.cancelled) throw Interrupted{};
  if (!args.quiet && ::isatty(STDERR_FILENO)) std::cerr << "\n";
  for (const std::string& note : run_notes(result)) std::cerr << "pdd: " << note << "\n";
  if (result.mesh.faces.empty())
    throw std::runtime_error("reconstruct: " + args.input +
                             ": the isosurface is empty (the solver found no surface)");

  begin_outputs();
  write_mesh(args.output, result.mesh, {args.ascii, &outputs});
  if (!args.domain_output.empty())
    write_domain_vtu(args.domain_output, result.domain.mesh(), result.domain.f(), {}, {},
                     &outputs);
  if (!args.stats_output.empty()) {
    const std::string json = statistics_json(result, args.options);
    outputs.add(args.stats_output, [&](std::ostream& out) { out << json; });
  }
  if (cancel_requested()) throw Interrupted{};
  outputs.commit();
  if (!args.quiet) std::cout << statistics_table(result);
  std::cout << "pdd: wrote " << args.output << " (" << result.mesh.faces.size() << " triangles, "
            << result.mesh.vertices.size() << " vertices";
  const IterationStats& last = result.iterations.back();
  for (const auto& [r, kind] : {std::pair(last.small_components, "small"),
                                std::pair(last.open_components, "open"),
                                std::pair(last.unsupported_components, "unsupported")})
    if (r.components > 0)
      std::cout << "; " << r.components << " " << kind << " component"
                << (r.components == 1 ? "" : "s") << " of " << r.faces << " triangles removed";
  if (last.handles.handles > 0)
    std::cout << "; " << last.handles.handles << " unsupported handle"
              << (last.handles.handles == 1 ? "" : "s") << " cut";
  std::cout << ")\n";
}

}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct",
      "Reconstruct a closed triangle mesh from a point set (normals estimated when it has none)");
  cmd->add_option("INPUT", args->input, "Point set: .ply .xyz .pwn .xyzn .off .obj")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh: .ply .off .obj")->required();
  // The options that shape the run: the library's table, shared with the Python module.
  add_table_options(cmd, args->values, [](const std::string&) { return true; });
  cmd->add_option("--domain-out", args->domain_output,
                  "Also write the final domain (tetrahedra and f) as a .vtu for ParaView");
  cmd->add_option("--stats", args->stats_output, "Write per-iteration statistics as JSON");
  cmd->add_option("--save-iterations", args->iterations_dir,
                  "Write the isosurface (.ply) and domain (.vtu) of every iteration to this "
                  "folder (created if missing)");
  cmd->add_flag("--quiet", args->quiet, "No progress line and no statistics table");
  cmd->add_flag("--ascii", args->ascii, "Write a .ply output as ASCII instead of binary");
  cmd->callback([args] { reconstruct(*args); });
}

}  // namespace pdd::cli
