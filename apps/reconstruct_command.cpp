// `pdd reconstruct INPUT -o OUTPUT [options]`: parse the options, read and
// validate the points, run the progressive pipeline (§3), write the mesh.
#include <pdd/io.h>
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

#include "commands.h"
#include "validators.h"

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
  std::string solver = to_string(ReconstructOptions{}.solver.kind);  // ssd | poisson | spectral
  std::string linear = to_string(ReconstructOptions{}.solver.linear.method);  // multigrid | cholmod
  std::string strategy = to_string(ReconstructOptions{}.strategy);   // progressive | ...
  std::string sizing = "uniform";                                     // uniform | adaptive
  std::string max_memory;     // "" (the default budget) or a size such as 8G
  ReconstructOptions options;
  bool ascii = false;  // PLY output as ASCII instead of binary
  bool quiet = false;  // no progress line, no table
  bool no_cleanup = false;  // keep the raw marching-tetrahedra isosurface
};

// Why the chosen solver needs normals, for the message when they are absent.
std::string why_normals(SolverKind solver) {
  switch (solver) {
    case SolverKind::kPoisson:
      return "the Poisson solver needs oriented normals (Eq. 13)";
    case SolverKind::kSpectral:
      return "the spectral solver needs normals, oriented or not (Eq. 16)";
    case SolverKind::kSsd:
      break;
  }
  return "the SSD solver fits the gradient of f to oriented normals (Eq. 15)";
}

// The progress line on stderr: rewritten in place on a terminal, one plain
// line per stage otherwise.
ProgressCallback progress_printer() {
  const bool terminal = ::isatty(STDERR_FILENO);
  return [terminal](const Progress& p) {
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

// --save-iterations: the isosurface and the domain after every solve (Figure 7).
IterationCallback iteration_writer(const std::string& folder, bool ascii) {
  std::filesystem::create_directories(folder);
  return [folder, ascii](const IterationStats& stats, const Domain& domain,
                         const TriangleMesh& isosurface) {
    char name[64];
    std::snprintf(name, sizeof name, "/iteration_%02d", stats.iteration);
    write_mesh(folder + name + "_isosurface.ply", isosurface, {ascii});
    write_domain_vtu(folder + name + "_domain.vtu", domain.mesh(), domain.f());
  };
}

void reconstruct(ReconstructArgs& args) {
  args.options.solver.kind = parse_solver_kind(args.solver);
  args.options.solver.linear.method = parse_linear_method(args.linear);
  args.options.strategy = parse_domain_strategy(args.strategy);
  args.options.sizing = parse_sizing_kind(args.sizing);
  if (!args.max_memory.empty()) args.options.max_memory = parse_memory_size(args.max_memory);
  // Output paths first, so that a typo costs nothing.
  check_output_path(args.output, OutputKind::kMesh);
  if (!args.domain_output.empty()) check_output_path(args.domain_output, OutputKind::kDomain);
  if (!args.stats_output.empty()) check_output_path(args.stats_output, OutputKind::kStatistics);

  ValidationReport report;
  const PointSet points = read_points(args.input, &report);
  for (const std::string& warning : report.warnings) {
    std::cerr << "pdd: warning: " << warning << "\n";
  }
  require_normals(points, args.input, why_normals(args.options.solver.kind));

  if (!args.quiet) args.options.progress = progress_printer();
  args.options.cleanup = !args.no_cleanup;
  if (!args.iterations_dir.empty())
    args.options.on_iteration = iteration_writer(args.iterations_dir, args.ascii);
  const Result result = pdd::reconstruct(points, args.options);
  if (!args.quiet && ::isatty(STDERR_FILENO)) std::cerr << "\n";
  if (const std::string note = memory_budget_note(result); !note.empty())
    std::cerr << "pdd: " << note << "\n";
  if (result.mesh.faces.empty())
    throw std::runtime_error("reconstruct: " + args.input +
                             ": the isosurface is empty (the solver found no surface)");

  write_mesh(args.output, result.mesh, {args.ascii});
  if (!args.domain_output.empty())
    write_domain_vtu(args.domain_output, result.domain.mesh(), result.domain.f());
  if (!args.stats_output.empty()) {
    const std::string json = statistics_json(result, args.options);
    write_atomically(args.stats_output, [&](std::ostream& out) { out << json; });
  }
  if (!args.quiet) std::cout << statistics_table(result);
  std::cout << "pdd: wrote " << args.output << " (" << result.mesh.faces.size() << " triangles, "
            << result.mesh.vertices.size() << " vertices";
  const IterationStats& last = result.iterations.back();
  for (const auto& [r, kind] : {std::pair(last.small_components, "small"),
                                std::pair(last.open_components, "open")})
    if (r.components > 0)
      std::cout << "; " << r.components << " " << kind << " component"
                << (r.components == 1 ? "" : "s") << " of " << r.faces << " triangles removed";
  std::cout << ")\n";
}

}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct", "Reconstruct a closed triangle mesh from a point set with normals");
  cmd->add_option("INPUT", args->input, "Point set: .ply .xyz .pwn .xyzn .off .obj")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh: .ply .off .obj")->required();
  cmd->add_option("--solver", args->solver, "Implicit solver (§3.5)")
      ->check(CLI::IsMember({"ssd", "poisson", "spectral"}))
      ->capture_default_str();
  cmd->add_option("--value-weight", args->options.solver.ssd.alpha,
                  "SSD: weight alpha of f(p) = 0 at the samples (Eq. 15); larger follows the "
                  "points more closely, smaller smooths their noise (default: from the input's "
                  "estimated noise sigma, 0.035 / (sigma / l)^2 up to 6e4, l the bounding box's "
                  "largest side)")
      ->check(greater_than(0));
  cmd->add_option("--linear", args->linear,
                  "Linear solves: multigrid (conjugate gradients preconditioned by V-cycles over "
                  "the earlier iterations' domains; CHOLMOD under 5000 unknowns) or cholmod "
                  "(always direct: the reference, memory and time superlinear)")
      ->check(CLI::IsMember({"multigrid", "cholmod"}))
      ->capture_default_str();
  cmd->add_option("--domain", args->strategy,
                  "How the domain is built (§4.2): progressive (ours), direct (refine without "
                  "optimizer or intermediate solves), input (input points + Delaunay "
                  "refinement), octree (octree nodes)")
      ->check(CLI::IsMember({"progressive", "direct", "input", "octree"}))
      ->capture_default_str();
  cmd->add_option("--sizing", args->sizing,
                  "Sizing field (§3.4): uniform (target area or edge) or adaptive (curvature)")
      ->check(CLI::IsMember({"uniform", "adaptive"}))
      ->capture_default_str();
  cmd->add_option("--target-edge", args->options.target_edge_length,
                  "Uniform sizing: target edge length of the output triangles "
                  "(default: the input's average spacing s while s is at most c = 1% of its "
                  "bounding-box diagonal, max(0.7 c, c^2 / s) for sparser inputs)")
      ->check(greater_than(0));
  cmd->add_option("--target-area", args->options.target_area,
                  "Uniform sizing: target isofacet area (overrides --target-edge)")
      ->check(greater_than(0));
  cmd->add_option("--tolerance", args->options.adaptive.tolerance,
                  "Adaptive sizing: distance tolerance d of s = 4 sqrt(3) (2d/c - d^2) "
                  "(default: s at the median curvature equals the uniform default)")
      ->check(greater_than(0));
  cmd->add_option("--gradation", args->options.adaptive.gradation,
                  "Adaptive sizing: exponent lambda of the curvature mapping")
      ->check(greater_than(0))
      ->capture_default_str();
  cmd->add_option("--iterations", args->options.max_iterations,
                  "At most this many solve-optimize-refine iterations")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--max-memory", args->max_memory,
                  "Memory the run may use, e.g. 8G or 500M (default: 3/4 of the memory "
                  "available at the start). A run whose sizing would outgrow it coarsens the "
                  "sizing and says so");
  cmd->add_option("--optimizer-rounds", args->options.optimizer_rounds,
                  "Optimizer passes (§3.3) on each refined domain, before it is solved on (0 "
                  "here and below leaves the refiner's slivers, on which SSD's system can lose "
                  "definiteness and the solve fail, as §4.5 found)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  cmd->add_option("--optimizer-rounds-before-refining",
                  args->options.optimizer_rounds_before_refining,
                  "Optimizer passes after each solve that the refiner follows")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  cmd->add_option("--hole-coarsening", args->options.away_from_data.max_factor,
                  "Target areas grow with the squared distance to the nearest input point "
                  "beyond 12 average spacings, up to this factor (holes, unseen sides; 1: off)")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--min-component-size", args->options.min_component_edges,
                  "Remove the components of the output whose bounding-box diagonal is under "
                  "this many mean edge lengths of the mesh (blobs below its resolution), and "
                  "those but the largest that the domain's boundary cuts open (0: keep all)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_flag("--no-cleanup", args->no_cleanup,
                "Output the marching-tetrahedra isosurface as it is, without the edge flips "
                "and needle collapses of the final clean-up");
  cmd->add_option("--cleanup-dihedral", args->options.cleanup_options.max_dihedral_degrees,
                  "Clean-up: flip or collapse only where neighbouring triangles turn by at "
                  "most this many degrees")
      ->check(CLI::Range(0.0, 89.9))
      ->capture_default_str();
  cmd->add_option("--domain-out", args->domain_output,
                  "Also write the final domain (tetrahedra and f) as a .vtu for ParaView");
  cmd->add_option("--stats", args->stats_output, "Write per-iteration statistics as JSON");
  cmd->add_option("--save-iterations", args->iterations_dir,
                  "Write the isosurface (.ply) and domain (.vtu) of every iteration to this "
                  "folder (created if missing)");
  cmd->add_option("--threads", args->options.threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "No progress line and no statistics table");
  cmd->add_option("--enlarge-ratio", args->options.domain.enlarge_ratio,
                  "Radius of the initial domain sphere over that of the points' bounding "
                  "sphere (§3.2)")
      ->check(greater_than(1))
      ->capture_default_str();
  cmd->add_option("--sphere-points", args->options.domain.sphere_points,
                  "Points spread on the initial domain sphere (§3.2)")
      ->check(CLI::Range(4, 1000000))
      ->capture_default_str();
  cmd->add_option("--radius-edge", args->options.domain.radius_edge_bound,
                  "Bound on the circumradius-to-shortest-edge ratio of the initial Delaunay "
                  "refinement (§3.2)")
      ->check(greater_than(0))
      ->capture_default_str();
  cmd->add_option("--lambda-asap", args->options.optimizer.lambda_asap,
                  "Weight λa of the as-similar-as-possible term (§3.3, Eq. 1)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--lambda-mid-edge", args->options.optimizer.lambda_mid_edge,
                  "Weight λm of the mid-edge term (§3.3, Eq. 1)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--damping", args->options.optimizer.damping_weight,
                  "Weight of the damping term, times the domain's diameter r(T) (§3.3)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed of the probabilistic bisection (§3.4)")
      ->capture_default_str();
  cmd->add_flag("--ascii", args->ascii, "Write a .ply output as ASCII instead of binary");
  cmd->callback([args] { reconstruct(*args); });
}

}  // namespace pdd::cli
