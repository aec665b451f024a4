// The optimizer of §3.3 on a real scan: Table 2, Figure 13 and Figure 14.
//
//   optimizer_bench [table2|figure14|all] [--points PATH] [--output DIR] [--iterations K]
//
// Defaults: all, data/kitten_scan.ply, bench/results, K = 6 (paths relative
// to the working directory). Writes DIR/optimizer_table2.txt (Table 2 and
// Figure 13) and DIR/optimizer_figure14.txt.
//
// The domain ("round 0"): Domain::initial, then K iterations of SSD solve +
// refinement with the uniform sizing (edge = the average spacing, §3.4), with one
// ASAP round before each solve but the first and none after the last
// refinement. Table 2 / Figure 13 run pure ASAP rounds
// (lambda_m = 0) on it; after 0, 3, 5 and 10 rounds they count the CG
// iterations that reach a relative residual of 1e-10 from a zero guess on
// the SSD system of that domain, and record the dihedral angles.
// Figure 14 runs the progressive loop (solve, optimize, refine) K times per
// strategy, then solve, optimize, final solve, and contours; as in §4.5, the
// strategies without ASAP get one ASAP round before each solve but the first.
#include <pdd/contour.h>
#include <pdd/errors.h>
#include <pdd/fem.h>
#include <pdd/io.h>
#include <pdd/optimize.h>
#include <pdd/quality.h>
#include <pdd/refine.h>
#include <pdd/sizing.h>
#include <pdd/solvers.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace pdd;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

// Prints and keeps a line for the results file.
struct Log {
  std::ostringstream text;
  void operator()(const std::string& line) {
    std::cout << line << std::flush;
    text << line;
  }
};

// SSD with the automatic value weight, the input's noise estimated once for
// all the solver's solves, as reconstruct() does.
std::unique_ptr<ImplicitSolver> ssd_solver(LinearMethod method, const PointSet& input) {
  SolverOptions options;
  options.kind = SolverKind::kSsd;
  options.ssd.noise = estimate_noise(input);
  options.linear.method = method;
  options.linear.direct_below = 0;  // kMultigrid: multigrid CG on these small domains too
  options.linear.coarsest_size = 1000;
  options.linear.cg_tolerance = 1e-10;
  options.linear.cg_max_iterations = 1000000;
  return make_solver(options);
}


// Fraction of the crossing edges cut within 10% of their midpoint:
// |t - 1/2| <= 0.1 with t the crossing parameter.
double midpoint_fraction(const Domain& domain) {
  const auto& f = domain.f();
  std::size_t crossing = 0, near = 0;
  std::vector<std::pair<int, int>> seen;
  for (const auto& t : domain.tets())
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const int a = std::min(t[i], t[j]), b = std::max(t[i], t[j]);
        if ((f[a] < 0) == (f[b] < 0)) continue;
        seen.emplace_back(a, b);
      }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  for (const auto& [a, b] : seen) {
    ++crossing;
    near += std::abs(f[a] / (f[a] - f[b]) - 0.5) <= 0.1;
  }
  return crossing ? static_cast<double>(near) / crossing : 0.0;
}

std::string histogram_row(const Histogram& h) {
  std::size_t total = 0;
  for (std::size_t c : h.counts) total += c;
  std::string out;
  for (std::size_t c : h.counts) out += format(" %5.2f", total ? 100.0 * c / total : 0.0);
  return out;
}

std::string histogram_header(const Histogram& h) {
  std::string out;
  for (std::size_t i = 0; i < h.counts.size(); ++i)
    out += format(" %5.0f", h.lower + h.bin_width * static_cast<double>(i));
  return out;
}

// The paper's weights, lambda_a = lambda_m = 3 (§4.4), for comparison with its
// Table 2 and Figures 13-14; the library's default lambda_a is 60.
OptimizerOptions paper_weights() {
  OptimizerOptions o;
  o.lambda_asap = 3;
  o.lambda_mid_edge = 3;
  return o;
}

// One pure ASAP round (lambda_m = 0): as in the paper's ablation (§4.5), the
// solver is not run on a freshly refined domain without it (CHOLMOD finds the
// SSD matrix of such a domain numerically indefinite).
void asap_step(Domain& domain) {
  OptimizerOptions asap = paper_weights();
  asap.mid_edge = false;
  optimize_domain(domain, asap);
}

// Round 0: K times solve and refine, with one ASAP round before each solve
// but the first; f of the last refinement is interpolated, not solved.
Domain refined_domain(const PointSet& input, int iterations, Log& log) {
  auto solver = ssd_solver(LinearMethod::kCholmod, input);
  Domain domain = Domain::initial(input);
  const auto sizing = uniform_sizing(area_for_edge_length(average_spacing(input)));
  std::mt19937_64 rng(1);
  for (int k = 0; k < iterations; ++k) {
    if (k > 0) asap_step(domain);
    domain.set_f(solver->solve(domain, input));
    const RefinementStats r = refine(domain, *sizing, rng);
    log(format("  refine %d: %d crossing tets, %d trisected, %d bisected, %zu vertices\n", k + 1,
               r.crossing_tets, r.trisected, r.bisected, domain.num_vertices()));
  }
  return domain;
}

// Table 2 and Figure 13, for one set of optimizer options.
void asap_rounds(const Domain& start, const PointSet& input, const OptimizerOptions& options,
                 const std::string& name, Log& log) {
  log("\n" + name + "\n");
  log(format("%6s %8s %8s %10s %9s %10s %9s %8s %8s %9s\n", "rounds", "jacobi", "(s)", "residual",
             "cg+mg", "residual", "min dih", "< 10 %", "mean min", "E after"));
  Domain domain = start;
  auto solver = ssd_solver(LinearMethod::kMultigrid, input);
  std::vector<std::string> histograms;
  Histogram any;
  double energy = 0;
  for (int round = 0; round <= 10; ++round) {
    if (round == 0 || round == 3 || round == 5 || round == 10) {
      // Plain Eigen CG (Jacobi preconditioner) from 0, as in Table 2.
      const ConditioningProbe probe = ssd_conditioning_probe(domain, input);
      // The project's SSD solver, CG with multigrid V-cycles, from 0.
      int mg_iterations = -1;
      double mg_residual = 0;
      try {
        solver->solve(domain, input);
        mg_iterations = solver->stats().iterations;
        mg_residual = solver->stats().residual;
      } catch (const SolverError& e) {
        log(std::string("  cg+mg failed: ") + e.what() + "\n");
      }
      const TetQuality q = tet_quality(domain.mesh());
      log(format("%6d %8ld %8.2f %10.3g %9d %10.3g %9.3f %8.3f %8.2f %9.3g\n", round,
                 probe.iterations, probe.seconds, probe.residual, mg_iterations, mg_residual,
                 q.min_dihedral, 100 * q.fraction_min_dihedral_below_10, q.mean_min_dihedral,
                 energy));
      histograms.push_back(format("%6d", round) + histogram_row(q.dihedral_histogram));
      any = q.dihedral_histogram;
    }
    if (round < 10) energy = optimize_domain(domain, options).energy_after;
  }
  log("\nFigure 13: dihedral angles, % of all 6|T| angles per 10-degree bin (bin start)\n");
  log(format("%6s", "rounds") + histogram_header(any) + "\n");
  for (const auto& h : histograms) log(h + "\n");
}

// Figure 14: one strategy of the ablation.
struct Strategy {
  std::string name;
  bool optimize;
  OptimizerOptions options;
};

void ablation(const PointSet& input, int iterations, Log& log) {
  OptimizerOptions mid_edge_only = paper_weights(), asap_only = paper_weights(),
                   both = paper_weights();
  mid_edge_only.asap = false;
  asap_only.mid_edge = false;
  const std::vector<Strategy> strategies = {{"non-optimized", false, both},
                                            {"mid-edge only", true, mid_edge_only},
                                            {"ASAP only", true, asap_only},
                                            {"ASAP + mid-edge", true, both}};
  const auto sizing = uniform_sizing(area_for_edge_length(average_spacing(input)));
  std::vector<std::string> histograms;
  Histogram any;
  log(format("%-16s %8s %9s %9s %7s %7s %7s %7s %10s %9s %7s\n", "strategy", "vertices", "triangles",
             "mean min", "min", "< 10 %", "< 20 %", "< 30 %", "mid 10 %", "min dih", "s"));
  for (const Strategy& s : strategies) {
    const auto t0 = Clock::now();
    const bool runs_asap = s.optimize && s.options.asap;
    auto solver = ssd_solver(LinearMethod::kCholmod, input);
    Domain domain = Domain::initial(input);
    std::mt19937_64 rng(1);
    for (int k = 0; k <= iterations; ++k) {
      if (k > 0 && !runs_asap) asap_step(domain);  // §4.5: before the solver
      domain.set_f(solver->solve(domain, input));
      if (s.optimize) optimize_domain(domain, s.options);
      if (k < iterations) refine(domain, *sizing, rng);
    }
    if (!runs_asap) asap_step(domain);
    domain.set_f(solver->solve(domain, input));  // the final solve, on the optimized domain
    const IsoSurface iso = marching_tetrahedra(domain.mesh(), domain.f());
    const TriangleQuality q = triangle_quality(iso.mesh);
    const TetQuality tq = tet_quality(domain.mesh());
    log(format("%-16s %8zu %9zu %9.2f %7.2f %7.2f %7.2f %7.2f %10.2f %9.2f %7.1f\n", s.name.c_str(),
               domain.num_vertices(), q.count, q.mean_min_angle, q.min_angle,
               100 * q.fraction_below_10, 100 * q.fraction_below_20, 100 * q.fraction_below_30,
               100 * midpoint_fraction(domain), tq.min_dihedral, seconds_since(t0)));
    histograms.push_back(format("%-16s", s.name.c_str()) + histogram_row(q.min_angle_histogram));
    any = q.min_angle_histogram;
  }
  log("\nFigure 14: isofacet (triangle) smallest angles, % of triangles per 5-degree bin (bin start)\n");
  log(format("%-16s", "strategy") + histogram_header(any) + "\n");
  for (const auto& h : histograms) log(h + "\n");
}

void write(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << text;
  std::cout << "wrote " << path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string which = "all", points = "data/kitten_scan.ply", output = "bench/results";
  int iterations = 6;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--points" && i + 1 < argc) {
      points = argv[++i];
    } else if (arg == "--output" && i + 1 < argc) {
      output = argv[++i];
    } else if (arg == "--iterations" && i + 1 < argc) {
      iterations = std::atoi(argv[++i]);
    } else if (arg == "table2" || arg == "figure14" || arg == "all") {
      which = arg;
    } else {
      std::cerr << "usage: optimizer_bench [table2|figure14|all] [--points PATH] [--output DIR] "
                   "[--iterations K]\n";
      return 2;
    }
  }
  try {
    const PointSet input = read_points(points);
    const std::string header = format("input: %s, %zu points; %d refinement iterations\n",
                                      points.c_str(), input.size(), iterations);
    if (which == "table2" || which == "all") {
      Log log;
      log("Table 2 / Figure 13 (optimizer_bench)\n" + header);
      const auto t0 = Clock::now();
      const Domain start = refined_domain(input, iterations, log);
      log(format("round-0 domain: %zu vertices, %zu tets (%.1f s)\n", start.num_vertices(),
                 start.num_tets(), seconds_since(t0)));
      Domain with_points = Domain::initial(input);
      with_points.insert(input.points);
      with_points.set_f(ssd_solver(LinearMethod::kCholmod, input)->solve(with_points, input));
      for (const Domain* domain : std::vector<const Domain*>{&start, &with_points}) {
        const std::string name = domain == &start ? "refined domain" : "initial domain + input points";
        if (domain == &with_points)
          log(format("\n%s: %zu vertices, %zu tets\n", name.c_str(), domain->num_vertices(),
                     domain->num_tets()));
        OptimizerOptions asap = paper_weights();
        asap.mid_edge = false;
        asap_rounds(*domain, input, asap, name + ", pure ASAP rounds (lambda_m = 0, damping on)", log);
        asap.damping = false;
        asap_rounds(*domain, input, asap,
                    name + ", pure ASAP rounds (lambda_m = 0, damping off; hull fixed)", log);
      }
      write(output + "/optimizer_table2.txt", log.text.str());
    }
    if (which == "figure14" || which == "all") {
      Log log;
      log("Figure 14 (optimizer_bench)\n" + header);
      ablation(input, iterations, log);
      write(output + "/optimizer_figure14.txt", log.text.str());
    }
  } catch (const std::exception& e) {
    std::cerr << "optimizer_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
