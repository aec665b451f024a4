// `pdd reconstruct INPUT -o OUTPUT [options]`: parse the options, read and
// validate the points, run the progressive pipeline (§3), write the mesh.
#include <pdd/io.h>
#include <pdd/pipeline.h>
#include <pdd/solvers.h>

#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "commands.h"

namespace pdd::cli {

namespace {

// The arguments of `pdd reconstruct`. The pipeline's options carry the
// paper's defaults (§3.2, §3.3); the command line only exposes them.
struct ReconstructArgs {
  std::string input;          // the point set (.ply .xyz .pwn .xyzn .off .obj)
  std::string output;         // the mesh (.ply .off .obj)
  std::string domain_output;  // "" or a .vtu for the final domain with f
  std::string solver = to_string(ReconstructOptions{}.solver.kind);  // ssd | poisson | spectral
  ReconstructOptions options;
  bool ascii = false;  // PLY output as ASCII instead of binary
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

void reconstruct(ReconstructArgs& args) {
  args.options.solver.kind = parse_solver_kind(args.solver);
  // Output paths first, so that a typo costs nothing.
  check_output_path(args.output, OutputKind::kMesh);
  if (!args.domain_output.empty()) check_output_path(args.domain_output, OutputKind::kDomain);

  ValidationReport report;
  const PointSet points = read_points(args.input, &report);
  for (const std::string& warning : report.warnings) {
    std::cerr << "pdd: warning: " << warning << "\n";
  }
  require_normals(points, args.input, why_normals(args.options.solver.kind));

  // The progressive pipeline (§3) comes here: reconstruct(points,
  // args.options), then write_mesh(args.output, mesh, {args.ascii}).
  throw std::runtime_error("reconstruct: the progressive pipeline is not implemented yet");
}

// A validator accepting numbers strictly greater than `bound`.
CLI::Validator greater_than(double bound) {
  std::ostringstream text;
  text << bound;
  const std::string limit = text.str();
  return CLI::Validator(
      [bound, limit](std::string& value) -> std::string {
        std::istringstream in(value);
        double number = 0;
        if (in >> number && in.eof() && number > bound) return "";
        return "must be a number greater than " + limit;
      },
      "NUMBER>" + limit);
}

}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct", "Reconstruct a closed triangle mesh from a point set with normals");
  cmd->add_option("INPUT", args->input, "Point set: .ply .xyz .pwn .xyzn .off .obj")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh: .ply .off .obj")->required();
  cmd->add_option("--domain", args->domain_output,
                  "Also write the final domain (tetrahedra and f) as a .vtu for ParaView");
  cmd->add_option("--solver", args->solver, "Implicit solver (§3.5)")
      ->check(CLI::IsMember({"ssd", "poisson", "spectral"}))
      ->capture_default_str();
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
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--lambda-mid-edge", args->options.optimizer.lambda_mid_edge,
                  "Weight λm of the mid-edge term (§3.3, Eq. 1)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--damping", args->options.optimizer.damping_weight,
                  "Weight of the damping term, times the domain's diameter r(T) (§3.3)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed of the probabilistic bisection (§3.4)")
      ->capture_default_str();
  cmd->add_flag("--ascii", args->ascii, "Write a .ply output as ASCII instead of binary");
  cmd->callback([args] { reconstruct(*args); });
}

}  // namespace pdd::cli
