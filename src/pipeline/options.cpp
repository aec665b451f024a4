#include <pdd/errors.h>
#include <pdd/options.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "common/quote.h"

namespace pdd {
namespace {

using Kind = OptionSpec::Kind;

std::string text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.15g", x);
  return buffer;
}

[[noreturn]] void reject(const std::string& name, const std::string& what,
                         const std::string& value) {
  throw InputError("--" + name + ": must be " + what + ", got " + quote(value));
}

using DoubleField = double& (*)(ReconstructOptions&);
using IntField = int& (*)(ReconstructOptions&);

// A finite double within (lower, upper] or [lower, upper], upper inclusive.
OptionSpec number(std::string name, std::string help, DoubleField field, double lower,
                  bool lower_inclusive, double upper, bool derived_default = false) {
  std::string what = "a number " + std::string(lower_inclusive ? ">= " : "> ") + text(lower);
  if (std::isfinite(upper)) what += " and <= " + text(upper);
  ReconstructOptions defaults;
  const std::string default_text = derived_default ? "" : text(field(defaults));
  auto set = [name, field, lower, lower_inclusive, upper, what](ReconstructOptions& o,
                                                                const std::string& v) {
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(v.c_str(), &end);
    const bool parsed = !v.empty() && end == v.c_str() + v.size() && errno == 0;
    if (!parsed || !std::isfinite(x) || (lower_inclusive ? x < lower : x <= lower) || x > upper)
      reject(name, what, v);
    field(o) = x;
  };
  return {std::move(name), Kind::kNumber, std::move(help), {}, default_text, set};
}

OptionSpec integer(std::string name, std::string help, IntField field, int lower, int upper) {
  const std::string what = "an integer from " + std::to_string(lower) + " to " +
                           std::to_string(upper);
  ReconstructOptions defaults;
  auto set = [name, field, lower, upper, what](ReconstructOptions& o, const std::string& v) {
    char* end = nullptr;
    errno = 0;
    const long long x = std::strtoll(v.c_str(), &end, 10);
    if (v.empty() || end != v.c_str() + v.size() || errno != 0 || x < lower || x > upper)
      reject(name, what, v);
    field(o) = static_cast<int>(x);
  };
  return {std::move(name), Kind::kInteger, std::move(help), {},
          std::to_string(field(defaults)), set};
}

template <typename Enum>
OptionSpec choice(std::string name, std::string help, std::vector<std::string> choices,
                  Enum (*parse)(const std::string&), Enum& (*field)(ReconstructOptions&),
                  std::string default_text) {
  std::string what = "one of";
  for (std::size_t i = 0; i < choices.size(); ++i) what += (i ? ", " : " ") + choices[i];
  auto set = [name, choices, parse, field, what](ReconstructOptions& o, const std::string& v) {
    bool known = false;
    for (const std::string& c : choices) known = known || c == v;
    if (!known) reject(name, what, v);
    field(o) = parse(v);
  };
  return {std::move(name), Kind::kChoice, std::move(help), std::move(choices),
          std::move(default_text), set};
}

SizingKind parse_sizing(const std::string& v) { return parse_sizing_kind(v); }

std::vector<OptionSpec> make_specs() {
  const ReconstructOptions d;
  std::vector<OptionSpec> s;
  s.push_back(choice<SolverKind>(
      "solver", "Implicit solver (§3.5)", {"ssd", "poisson", "spectral"}, parse_solver_kind,
      [](ReconstructOptions& o) -> SolverKind& { return o.solver.kind; },
      to_string(d.solver.kind)));
  s.push_back(choice<NormalsMode>(
      "normals",
      "The input's normals: keep (use them; points without normals get estimated ones), "
      "orient (keep their directions, orient them anew: for normals whose signs cannot be "
      "trusted), estimate (replace them by estimated ones)",
      {"keep", "orient", "estimate"}, parse_normals_mode,
      [](ReconstructOptions& o) -> NormalsMode& { return o.normals; }, to_string(d.normals)));
  s.push_back(choice<Orientation>(
      "orientation",
      "How estimated or re-oriented normals get their signs: visibility (segments of "
      "consistent normals, each turned towards the side from which more rays escape past the "
      "points: the outside, of closed shapes and open scans alike; where most are seen from "
      "both sides, as in a one-sided scan, those take the spectral vote), spectral (the same "
      "segments, each turned by its majority along the gradient of a coarse run of the "
      "spectral solver, which needs no orientation) or mst (propagation along a minimum "
      "spanning tree of the neighbour graph, the peers' method)",
      {"visibility", "spectral", "mst"}, parse_orientation,
      [](ReconstructOptions& o) -> Orientation& { return o.orientation; },
      to_string(d.orientation)));
  s.push_back(integer("normal-neighbors",
                      "Neighbours of each point for the normals' estimation (jet fitting; more, "
                      "up to 100, on points whose estimated noise is over a quarter of their "
                      "spacing) and the minimum spanning tree",
                      [](ReconstructOptions& o) -> int& { return o.normal_neighbors; }, 6,
                      1000));
  s.push_back(number(
      "outliers",
      "Drop the points whose mean distance to their 16 nearest points is over this many times "
      "that of those neighbours, before the solve; they are counted and reported (0: keep all)",
      [](ReconstructOptions& o) -> double& { return o.outliers.ratio; }, 0, true, 1000));
  s.push_back(number(
      "value-weight",
      "SSD: weight alpha of f(p) = 0 at the samples (Eq. 15); larger follows the points more "
      "closely, smaller smooths their noise (default: from the input's estimated noise sigma, "
      "0.035 / (sigma / l)^2 up to 6e4, l the bounding box's largest side)",
      [](ReconstructOptions& o) -> double& { return o.solver.ssd.alpha; }, 0, false,
      HUGE_VAL, true));
  s.push_back(choice<LinearMethod>(
      "linear",
      "Linear solves: multigrid (conjugate gradients preconditioned by V-cycles over the "
      "earlier iterations' domains; CHOLMOD under 5000 unknowns) or cholmod (always direct: "
      "the reference, memory and time superlinear)",
      {"multigrid", "cholmod"}, parse_linear_method,
      [](ReconstructOptions& o) -> LinearMethod& { return o.solver.linear.method; },
      to_string(d.solver.linear.method)));
  s.push_back(choice<DomainStrategy>(
      "domain",
      "How the domain is built (§4.2): progressive (ours), direct (refine without optimizer "
      "or intermediate solves), input (input points + Delaunay refinement), octree (octree "
      "nodes)",
      {"progressive", "direct", "input", "octree"}, parse_domain_strategy,
      [](ReconstructOptions& o) -> DomainStrategy& { return o.strategy; },
      to_string(d.strategy)));
  s.push_back(choice<SizingKind>(
      "sizing", "Sizing field (§3.4): uniform (target area or edge) or adaptive (curvature)",
      {"uniform", "adaptive"}, parse_sizing,
      [](ReconstructOptions& o) -> SizingKind& { return o.sizing; },
      d.sizing == SizingKind::kUniform ? "uniform" : "adaptive"));
  s.push_back(number(
      "target-edge",
      "Uniform sizing: target edge length of the output triangles (default: the input's "
      "average spacing s while s is at most c = 1% of its bounding-box diagonal, "
      "max(0.7 c, c^2 / s) for sparser inputs)",
      [](ReconstructOptions& o) -> double& { return o.target_edge_length; }, 0, false,
      HUGE_VAL, true));
  s.push_back(number("target-area",
                     "Uniform sizing: target isofacet area (overrides --target-edge)",
                     [](ReconstructOptions& o) -> double& { return o.target_area; }, 0, false,
                     HUGE_VAL, true));
  s.push_back(integer(
      "target-faces",
      "About this many output triangles (0: off): the sizing, uniform or adaptive, is scaled "
      "to it from the first iterations' isosurface (instead of --target-edge)",
      [](ReconstructOptions& o) -> int& { return o.target_faces; }, 0, 1000000000));
  s.push_back(number(
      "tolerance",
      "Adaptive sizing: distance tolerance d of s = 4 sqrt(3) (2d/c - d^2) (default: scaled so "
      "that the output has about 0.8x the triangles of the uniform default)",
      [](ReconstructOptions& o) -> double& { return o.adaptive.tolerance; }, 0, false,
      HUGE_VAL, true));
  s.push_back(number("gradation", "Adaptive sizing: exponent lambda of the curvature mapping",
                     [](ReconstructOptions& o) -> double& { return o.adaptive.gradation; }, 0,
                     false, HUGE_VAL));
  s.push_back(integer("iterations", "At most this many solve-optimize-refine iterations",
                      [](ReconstructOptions& o) -> int& { return o.max_iterations; }, 1, 1000));
  s.push_back({"max-memory", Kind::kSize,
               "Memory the run may use, e.g. 8G or 500M (default: 3/4 of the memory available "
               "at the start). A run whose sizing would outgrow it coarsens the sizing and says "
               "so",
               {}, "",
               [](ReconstructOptions& o, const std::string& v) {
                 o.max_memory = parse_memory_size(v, "--max-memory");
               }});
  s.push_back(integer(
      "optimizer-rounds",
      "Optimizer passes (§3.3) on each refined domain, before it is solved on (0 here and "
      "below leaves the refiner's slivers, on which SSD's system can lose definiteness and the "
      "solve fail, as §4.5 found)",
      [](ReconstructOptions& o) -> int& { return o.optimizer_rounds; }, 0, 100));
  s.push_back(integer(
      "optimizer-rounds-before-refining",
      "Optimizer passes after each solve that the refiner follows",
      [](ReconstructOptions& o) -> int& { return o.optimizer_rounds_before_refining; }, 0,
      100));
  s.push_back(number(
      "hole-coarsening",
      "Target areas grow with the squared distance to the nearest input point beyond 12 "
      "average spacings, up to this factor (holes, unseen sides; 1: off; with --trim, which "
      "cuts that surface away, 16 is faster on one-sided scans, and coarser near the data)",
      [](ReconstructOptions& o) -> double& { return o.away_from_data.max_factor; }, 1, true,
      1e6));
  s.push_back(number(
      "min-component-size",
      "Remove the components of the output whose bounding-box diagonal is under this many "
      "mean edge lengths of the mesh (blobs below its resolution), and those but the largest "
      "that the domain's boundary cuts open (0: keep all)",
      [](ReconstructOptions& o) -> double& { return o.min_component_edges; }, 0, true,
      HUGE_VAL));
  s.push_back(integer(
      "min-component-samples",
      "Remove the components of the output, but the largest, that are nearest to fewer than "
      "this many input points, or to fewer per area than a tenth of the whole output's: blobs "
      "and bubbles around stray points (0: keep all)",
      [](ReconstructOptions& o) -> int& { return o.min_component_samples; }, 0, 1000000000));
  s.push_back(number(
      "trim",
      "Keep only the surface within this many local sample spacings of the input points: an open "
      "mesh of what was scanned, cut along a smooth curve, instead of a closed surface that "
      "invents the unseen sides (0: closed; 2 suits most scans)",
      [](ReconstructOptions& o) -> double& { return o.trim.distance; }, 0, true, 100));
  s.push_back(number(
      "trim-holes",
      "With --trim: unsupported regions less than this many average sample spacings across "
      "(a scan's gaps) stay closed",
      [](ReconstructOptions& o) -> double& { return o.trim.holes; }, 0, true, 1e9));
  s.push_back(number(
      "trim-islands",
      "With --trim: pieces of the trimmed surface less than this many average sample spacings "
      "across that fewer than 2 input points lie on are dropped",
      [](ReconstructOptions& o) -> double& { return o.trim.islands; }, 0, true, 1e9));
  s.push_back({"attributes", Kind::kText,
               "Point attributes the output's vertices carry, interpolated from the nearest "
               "samples (PLY output; colours also to OFF and OBJ): colors, all, none, or "
               "property names separated by commas",
               {}, d.attributes,
               [](ReconstructOptions& o, const std::string& v) {
                 o.attributes = parse_attribute_selection(v);
               }});
  s.push_back({"keep-handles", Kind::kFlag,
               "Keep the handles of the output that its samples contradict (tunnels through "
               "walls, bridges across gaps thinner than the sample spacing), which are "
               "otherwise cut and capped",
               {}, d.handles.enabled ? "false" : "true",
               [](ReconstructOptions& o, const std::string& v) {
                 if (v != "true" && v != "false") reject("keep-handles", "true or false", v);
                 o.handles.enabled = v == "false";
               }});
  s.push_back({"no-cleanup", Kind::kFlag,
               "Output the marching-tetrahedra isosurface as it is, without the edge flips and "
               "needle collapses of the final clean-up",
               {}, d.cleanup ? "false" : "true",
               [](ReconstructOptions& o, const std::string& v) {
                 if (v != "true" && v != "false") reject("no-cleanup", "true or false", v);
                 o.cleanup = v == "false";
               }});
  s.push_back(number(
      "cleanup-dihedral",
      "Clean-up: flip or collapse only where neighbouring triangles turn by at most this many "
      "degrees",
      [](ReconstructOptions& o) -> double& { return o.cleanup_options.max_dihedral_degrees; },
      0, true, 89.9));
  s.push_back(integer("threads",
                      "Worker threads (0: all cores; at most 4 times the hardware threads)",
                      [](ReconstructOptions& o) -> int& { return o.threads; }, 0, max_threads()));
  s.push_back(number(
      "enlarge-ratio",
      "Radius of the initial domain sphere over that of the points' bounding sphere (§3.2)",
      [](ReconstructOptions& o) -> double& { return o.domain.enlarge_ratio; }, 1, false,
      DomainOptions::kMaxEnlargeRatio));
  s.push_back(integer("sphere-points", "Points spread on the initial domain sphere (§3.2)",
                      [](ReconstructOptions& o) -> int& { return o.domain.sphere_points; }, 4,
                      1000000));
  s.push_back(number(
      "radius-edge",
      "Bound on the circumradius-to-shortest-edge ratio of the initial Delaunay refinement "
      "(§3.2); at least 1, below which the refinement does not end",
      [](ReconstructOptions& o) -> double& { return o.domain.radius_edge_bound; },
      DomainOptions::kMinRadiusEdgeBound, true, HUGE_VAL));
  s.push_back(number("lambda-asap",
                     "Weight λa of the as-similar-as-possible term (§3.3, Eq. 1)",
                     [](ReconstructOptions& o) -> double& { return o.optimizer.lambda_asap; },
                     0, true, HUGE_VAL));
  s.push_back(number("lambda-mid-edge", "Weight λm of the mid-edge term (§3.3, Eq. 1)",
                     [](ReconstructOptions& o) -> double& {
                       return o.optimizer.lambda_mid_edge;
                     },
                     0, true, HUGE_VAL));
  s.push_back(number(
      "damping", "Weight of the damping term, times the domain's diameter r(T) (§3.3)",
      [](ReconstructOptions& o) -> double& { return o.optimizer.damping_weight; }, 0, true,
      HUGE_VAL));
  s.push_back({"seed", Kind::kSeed,
               "Seed of the probabilistic bisection (§3.4); the same seed gives the same output",
               {}, std::to_string(d.seed),
               [](ReconstructOptions& o, const std::string& v) {
                 char* end = nullptr;
                 errno = 0;
                 const unsigned long long x = std::strtoull(v.c_str(), &end, 10);
                 if (v.empty() || v[0] < '0' || v[0] > '9' || end != v.c_str() + v.size() ||
                     errno != 0)
                   reject("seed", "an integer from 0 to 18446744073709551615", v);
                 o.seed = x;
               }});
  return s;
}

}  // namespace

const std::vector<OptionSpec>& reconstruct_option_specs() {
  static const std::vector<OptionSpec> specs = make_specs();
  return specs;
}

void set_reconstruct_option(ReconstructOptions& options, const std::string& name,
                            const std::string& value) {
  std::string dashed = name;
  for (char& c : dashed)
    if (c == '_') c = '-';
  for (const OptionSpec& spec : reconstruct_option_specs())
    if (spec.name == dashed) return spec.set(options, value);
  throw InputError("unknown option " + quote(name));
}

}  // namespace pdd
