// The linear solve of SSD (Eq. 15) at growing sizes, by each route: CHOLMOD,
// CG + incomplete Cholesky (Eigen), CG + geometric multigrid over the
// progressive hierarchy (pdd's default) and, when built with hypre, CG +
// BoomerAMG. Records CG iterations to the default tolerance, setup and solve
// seconds, and peak memory.
//
//   solvers_bench [--inputs scan.ply,...] [--sizes 50000,200000,1000000]
//                 [--out bench/results/solvers.txt] [--direct-max 450000]
//                 [--tolerance 1e-6] [--routes cg+multigrid,cholmod]
//                 [--multigrid-variants 4:4:2,3:3]  (coarsening ratio:smoothing degree
//                 [:on the finest level])
//
// Domains, either
// - --inputs: the loop's own, from `pdd reconstruct` with default options on
//   each point set (every iteration's domain after its optimizer passes, as
//   the solver saw it; the samples without the run's outliers), or
// - --sizes: an ellipsoid's samples (1, 0.7, 0.5; exact normals, one sample
//   per 4 vertices) in Domain::initial, refined three times by a factor of 3
//   (two thirds of the new vertices in a shell around the surface, one third
//   spread through the ball) and optimized once, random domains of about
//   each size.
// The multigrid route solves the domains in order with one solver, so the
// earlier ones are its coarse levels, and reports the last solve; the other
// routes solve the last domain alone. Every route runs in its own child
// process (fork); its peak memory is the child's peak resident set less the
// parent's at the fork (the domains); with --inputs the routes run one after
// the other in this process, without peak memory (see run_isolated). CHOLMOD
// is skipped above --direct-max vertices, where its factor outgrows this
// machine.
#include <pdd/domain.h>
#include <pdd/io.h>
#include <pdd/optimize.h>
#include <pdd/outliers.h>
#include <pdd/pipeline.h>
#include <pdd/solvers.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#ifdef PDD_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>
#endif

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using pdd::Vec3;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

const Vec3 kAxes(1.0, 0.7, 0.5);

pdd::PointSet ellipsoid_samples(int n) {
  pdd::PointSet ps;
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 d(rho * std::cos(golden_angle * i), rho * std::sin(golden_angle * i), z);
    const Vec3 p = d.cwiseProduct(kAxes);
    ps.points.push_back(p);
    ps.normals.push_back(p.cwiseQuotient(kAxes.cwiseProduct(kAxes)).normalized());
  }
  return ps;
}

// Grows `domain` to about `target` vertices: two thirds of the new points
// near the surface (samples moved along the normal and sideways), one third
// uniform in the ball.
void grow(pdd::Domain& domain, const pdd::PointSet& samples, std::size_t target,
          std::mt19937& rng) {
  if (domain.num_vertices() >= target) return;
  const std::size_t extra = target - domain.num_vertices();
  std::uniform_int_distribution<int> pick(0, static_cast<int>(samples.size()) - 1);
  std::normal_distribution<double> g(0.0, 0.04);
  std::vector<Vec3> points;
  points.reserve(extra);
  while (points.size() < 2 * extra / 3) {
    const int k = pick(rng);
    points.push_back(samples.points[k] + g(rng) * samples.normals[k] +
                     0.5 * Vec3(g(rng), g(rng), g(rng)));
  }
  const double r = 0.85 * domain.radius();
  std::uniform_real_distribution<double> u(-r, r);
  while (points.size() < extra) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.norm() < r) points.push_back(domain.center() + p);
  }
  domain.insert(points);
}

// One optimizer round (§3.3), as the loop runs before each solve, with f an
// approximate signed distance to the ellipsoid for the mid-edge term.
void optimize(pdd::Domain& domain) {
  std::vector<double> f(domain.num_vertices());
  for (std::size_t v = 0; v < f.size(); ++v) {
    const Vec3& p = domain.vertices()[v];
    const double k = p.cwiseQuotient(kAxes).norm();
    f[v] = (k - 1) * p.norm() / std::max(k, 1e-12);
  }
  domain.set_f(f);
  pdd::optimize_domain(domain, pdd::OptimizerOptions());
}

// The domains of a default reconstruction of `path`, one per solve, and its
// samples as the solver saw them (without the outliers the run drops).
std::vector<pdd::Domain> loop_domains(const std::string& path, pdd::PointSet& samples) {
  pdd::PointSet points = pdd::read_points(path);
  const std::vector<char> stray = pdd::find_outliers(points.points);
  std::vector<char> keep(stray.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !stray[i];
  points.keep(keep);
  std::vector<pdd::Domain> domains;
  pdd::ReconstructOptions options;
  options.outliers.ratio = 0;  // dropped above
  options.on_iteration = [&](const pdd::IterationStats&, const pdd::Domain& d,
                             const pdd::TriangleMesh&) { domains.push_back(d); };
  pdd::reconstruct(points, options);
  samples = std::move(points);
  return domains;
}

struct Outcome {
  int iterations = 0;
  double residual = 0, setup = 0, solve = 0;
  int levels = 0;
  std::string note;
};

pdd::SolverOptions ssd_options(const pdd::PointSet& samples, double tolerance) {
  pdd::SolverOptions o;
  o.kind = pdd::SolverKind::kSsd;
  o.ssd.noise = pdd::estimate_noise(samples);
  o.linear.cg_tolerance = tolerance;
  return o;
}

double relative_residual(const pdd::LinearSystem& s, const Eigen::VectorXd& x) {
  return (s.A * x - s.b).norm() / s.b.norm();
}

Outcome run_cholmod(const std::vector<pdd::Domain>& domains, const pdd::PointSet& samples,
                    double tolerance) {
  pdd::SolverOptions o = ssd_options(samples, tolerance);
  o.linear.method = pdd::LinearMethod::kCholmod;
  auto solver = pdd::make_solver(o);
  solver->solve(domains.back(), samples);
  const pdd::SolverStats& s = solver->stats();
  return {s.iterations, s.residual, s.factorize_seconds, s.solve_seconds, 1, ""};
}

Outcome run_multigrid(const std::vector<pdd::Domain>& domains, const pdd::PointSet& samples,
                      double tolerance, double ratio = 0, int degree = 0, int finest = 0) {
  pdd::SolverOptions o = ssd_options(samples, tolerance);
  if (ratio > 0) o.linear.coarsening_ratio = ratio;
  if (degree > 0) o.linear.smoothing_degree = degree;
  if (finest > 0) o.linear.finest_smoothing_degree = finest;
  auto solver = pdd::make_solver(o);
  for (const pdd::Domain& d : domains) solver->solve(d, samples);
  const pdd::SolverStats& s = solver->stats();
  return {s.iterations, s.residual, s.factorize_seconds, s.solve_seconds, s.levels, ""};
}

// Eigen's CG with its incomplete Cholesky (the route pdd used before the
// multigrid), capped at 1000 iterations.
Outcome run_incomplete_cholesky(const std::vector<pdd::Domain>& domains,
                                const pdd::PointSet& samples, double tolerance) {
  const pdd::LinearSystem s = pdd::ssd_system(domains.back(), samples,
                                              ssd_options(samples, tolerance).ssd);
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double>>
      cg;
  cg.setTolerance(tolerance);
  cg.setMaxIterations(1000);
  auto start = Clock::now();
  cg.compute(s.A);
  Outcome out;
  out.setup = seconds_since(start);
  start = Clock::now();
  const Eigen::VectorXd x = cg.solve(s.b);
  out.solve = seconds_since(start);
  out.iterations = static_cast<int>(cg.iterations());
  out.residual = relative_residual(s, x);
  if (cg.info() != Eigen::Success) out.note = "not converged";
  return out;
}

#ifdef PDD_HAVE_HYPRE
// hypre's BoomerAMG (one V-cycle, HMIS coarsening, extended+i interpolation
// truncated to 4 entries, hybrid symmetric Gauss-Seidel) as the
// preconditioner of hypre's PCG, serial: the best of the settings tried
// (docs/benchmarks.md, "Multigrid").
Outcome run_boomeramg(const std::vector<pdd::Domain>& domains, const pdd::PointSet& samples,
                      double tolerance) {
  const pdd::LinearSystem s = pdd::ssd_system(domains.back(), samples,
                                              ssd_options(samples, tolerance).ssd);
  int argc = 0;
  char** argv = nullptr;
  MPI_Init(&argc, &argv);
  HYPRE_Init();
  const int n = static_cast<int>(s.A.rows());
  auto start = Clock::now();
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows = s.A;  // symmetric: rows = columns
  std::vector<int> counts(n), index(n);
  for (int i = 0; i < n; ++i) {
    counts[i] = rows.outerIndexPtr()[i + 1] - rows.outerIndexPtr()[i];
    index[i] = i;
  }
  HYPRE_IJMatrix A;
  HYPRE_IJMatrixCreate(MPI_COMM_WORLD, 0, n - 1, 0, n - 1, &A);
  HYPRE_IJMatrixSetObjectType(A, HYPRE_PARCSR);
  HYPRE_IJMatrixSetRowSizes(A, counts.data());
  HYPRE_IJMatrixInitialize(A);
  HYPRE_IJMatrixSetValues(A, n, counts.data(), index.data(), rows.innerIndexPtr(),
                          rows.valuePtr());
  HYPRE_IJMatrixAssemble(A);
  auto vector = [&](const double* values) {
    HYPRE_IJVector v;
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, 0, n - 1, &v);
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(v);
    HYPRE_IJVectorSetValues(v, n, index.data(), values);
    HYPRE_IJVectorAssemble(v);
    return v;
  };
  const std::vector<double> zero(n, 0.0);
  HYPRE_IJVector b = vector(s.b.data()), x = vector(zero.data());
  HYPRE_ParCSRMatrix pa;
  HYPRE_ParVector pb, px;
  HYPRE_IJMatrixGetObject(A, reinterpret_cast<void**>(&pa));
  HYPRE_IJVectorGetObject(b, reinterpret_cast<void**>(&pb));
  HYPRE_IJVectorGetObject(x, reinterpret_cast<void**>(&px));

  HYPRE_Solver pcg, amg;
  HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &pcg);
  HYPRE_PCGSetTol(pcg, tolerance);
  HYPRE_PCGSetMaxIter(pcg, 2000);
  HYPRE_PCGSetTwoNorm(pcg, 1);
  HYPRE_BoomerAMGCreate(&amg);
  HYPRE_BoomerAMGSetCoarsenType(amg, 10);
  HYPRE_BoomerAMGSetInterpType(amg, 6);
  HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
  HYPRE_BoomerAMGSetStrongThreshold(amg, 0.5);
  HYPRE_BoomerAMGSetRelaxType(amg, 6);
  HYPRE_BoomerAMGSetNumSweeps(amg, 1);
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);
  HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  HYPRE_ParCSRPCGSetup(pcg, pa, pb, px);
  Outcome out;
  out.setup = seconds_since(start);
  start = Clock::now();
  HYPRE_ParCSRPCGSolve(pcg, pa, pb, px);
  out.solve = seconds_since(start);
  HYPRE_PCGGetNumIterations(pcg, &out.iterations);
  Eigen::VectorXd solution(n);
  HYPRE_IJVectorGetValues(x, n, index.data(), solution.data());
  out.residual = relative_residual(s, solution);
  out.note = "serial (Debian's hypre has no OpenMP)";
  HYPRE_Finalize();
  MPI_Finalize();
  return out;
}
#endif

struct Route {
  const char* name;
  std::function<Outcome(const std::vector<pdd::Domain>&, const pdd::PointSet&, double)> run;
  bool always = false;  // run whatever --routes says (the --multigrid-variants)
};

// A route's line of the report, without the peak memory.
std::string outcome_line(const char* name, const Outcome& o) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-13s %6d %9.1e %7d %9.2f %9.2f", name, o.iterations, o.residual,
                o.levels, o.setup, o.solve);
  return o.note.empty() ? std::string(buf) : buf + ("  (" + o.note + ")");
}

long resident_kb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return 0;
}

// Runs the route in a child process; its line with the peak memory added.
std::string run_isolated(const Route& route, const std::vector<pdd::Domain>& domains,
                         const pdd::PointSet& samples, double tolerance, bool fork_child) {
  if (!fork_child) {
    // In this process, without the peak memory: a child forked after the loop (--inputs)
    // waits forever in CHOLMOD's OpenMP, whose thread pool the fork does not copy.
    try {
      return outcome_line(route.name, route.run(domains, samples, tolerance)) + " | in process";
    } catch (const std::exception& e) {
      return std::string(route.name) + " FAILED: " + e.what();
    }
  }
  int fd[2];
  if (pipe(fd) != 0) return "pipe failed";
  const long parent_kb = resident_kb();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    char buf[512];
    try {
      const Outcome o = route.run(domains, samples, tolerance);
      const std::string line = outcome_line(route.name, o);
      if (write(fd[1], line.data(), line.size()) < 0) _exit(1);
    } catch (const std::exception& e) {
      std::snprintf(buf, sizeof buf, "%-13s FAILED: %s", route.name, e.what());
      if (write(fd[1], buf, std::strlen(buf)) < 0) _exit(1);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string line;
  char buf[4096];
  ssize_t n;
  while ((n = read(fd[0], buf, sizeof buf)) > 0) line.append(buf, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  struct rusage usage;
  wait4(pid, &status, 0, &usage);
  if (line.empty()) line = std::string(route.name) + " CRASHED";
  char mem[64];
  std::snprintf(mem, sizeof mem, " | %7.0f", (usage.ru_maxrss - parent_kb) / 1024.0);
  return line + mem;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes = {50000, 200000, 1000000};
  std::vector<std::string> inputs;
  std::string out_path = "bench/results/solvers.txt";
  std::size_t direct_max = 450000;
  double tolerance = 1e-6;
  struct Variant {
    double ratio;
    int degree, finest;
  };
  std::vector<Variant> variants;  // --multigrid-variants ratio:degree[:finest],...
  std::string only;  // the routes to run, comma-separated between commas; all when empty
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream ss(argv[i + 1]);
      std::string item;
      while (std::getline(ss, item, ',')) sizes.push_back(std::stoul(item));
    } else if (!std::strcmp(argv[i], "--inputs")) {
      std::stringstream ss(argv[i + 1]);
      std::string item;
      while (std::getline(ss, item, ',')) inputs.push_back(item);
    } else if (!std::strcmp(argv[i], "--out")) {
      out_path = argv[i + 1];
    } else if (!std::strcmp(argv[i], "--direct-max")) {
      direct_max = std::stoul(argv[i + 1]);
    } else if (!std::strcmp(argv[i], "--tolerance")) {
      tolerance = std::stod(argv[i + 1]);
    } else if (!std::strcmp(argv[i], "--multigrid-variants")) {
      std::stringstream ss(argv[i + 1]);
      std::string item;
      while (std::getline(ss, item, ',')) {
        std::stringstream fields(item);
        std::string ratio, degree, finest;
        std::getline(fields, ratio, ':');
        std::getline(fields, degree, ':');
        std::getline(fields, finest, ':');
        variants.push_back({std::stod(ratio), std::stoi(degree),
                            finest.empty() ? std::stoi(degree) : std::stoi(finest)});
      }
    } else if (!std::strcmp(argv[i], "--routes")) {
      only = "," + std::string(argv[i + 1]) + ",";
    }
  }
  std::vector<Route> routes = {
      {"cg+multigrid",
       [](const std::vector<pdd::Domain>& d, const pdd::PointSet& s, double t) {
         return run_multigrid(d, s, t);
       }},
      {"cg+ic", run_incomplete_cholesky},
#ifdef PDD_HAVE_HYPRE
      {"cg+boomeramg", run_boomeramg},
#endif
      {"cholmod", run_cholmod},
  };
  // The multigrid with other coarsening ratios and smoothing degrees, in turn with the default.
  std::vector<std::string> variant_names;
  for (const auto& [ratio, degree, finest] : variants) {
    std::ostringstream name;
    name << "mg r" << ratio << " d" << degree << " f" << finest;
    variant_names.push_back(name.str());
  }
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const auto [ratio, degree, finest] = variants[k];
    routes.push_back({variant_names[k].c_str(),
                      [ratio, degree, finest](const std::vector<pdd::Domain>& d,
                                              const pdd::PointSet& s, double t) {
                        return run_multigrid(d, s, t, ratio, degree, finest);
                      },
                      /*always=*/true});
  }

  std::ostringstream report;
  report << "# solvers_bench: SSD (Eq. 15) on progressive domains, relative"
         << " tolerance " << tolerance << "\n"
         << "# columns: route, CG iterations, |Ax-b|/|b|, multigrid levels, setup s, solve s"
         << " | peak MB over the domains'\n";
#ifndef PDD_HAVE_HYPRE
  report << "# built without hypre: no BoomerAMG route (bench/solvers.sh installs libhypre-dev)\n";
#endif
  std::cout << report.str();
  // Each case: its domains (the last is solved) and samples.
  const std::size_t cases = inputs.empty() ? sizes.size() : inputs.size();
  for (std::size_t which = 0; which < cases; ++which) {
    const auto start = Clock::now();
    pdd::PointSet samples;
    std::vector<pdd::Domain> domains;
    std::string origin;
    if (!inputs.empty()) {
      domains = loop_domains(inputs[which], samples);
      origin = inputs[which] + " (the loop's domains)";
    } else {
      const std::size_t target = sizes[which];
      std::mt19937 rng(7);
      samples = ellipsoid_samples(static_cast<int>(std::max<std::size_t>(2000, target / 4)));
      domains.push_back(pdd::Domain::initial(samples));
      grow(domains.back(), samples, target / 27, rng);
      for (std::size_t k : {9, 3, 1}) {
        domains.push_back(domains.back());
        grow(domains.back(), samples, target / k, rng);
        optimize(domains.back());
      }
      origin = "ellipsoid (random domains)";
    }
    std::ostringstream head;
    head << "\n## " << origin << ": " << domains.back().num_vertices() << " vertices, "
         << domains.back().num_tets() << " tets, " << samples.size() << " samples; earlier domains";
    for (std::size_t k = 0; k + 1 < domains.size(); ++k) head << " " << domains[k].num_vertices();
    head << " (built in " << seconds_since(start) << " s)\n";
    std::cout << head.str() << std::flush;
    report << head.str();
    for (const Route& r : routes) {
      if (!r.always && !only.empty() && only.find("," + std::string(r.name) + ",") == std::string::npos)
        continue;
      std::string line;
      if (!std::strcmp(r.name, "cholmod") && domains.back().num_vertices() > direct_max)
        line = "cholmod       skipped: over --direct-max";
      else
        line = run_isolated(r, domains, samples, tolerance, inputs.empty());
      std::cout << line << "\n" << std::flush;
      report << line << "\n";
    }
  }
  std::ofstream out(out_path);
  if (!out) {
    std::cerr << "solvers_bench: cannot write " << out_path << "\n";
    return 1;
  }
  out << report.str();
  std::cout << "\nwritten to " << out_path << "\n";
  return 0;
}
