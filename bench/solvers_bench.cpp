// Times the three solvers of §3.5 on domains of about 10k, 50k and 200k
// vertices, for each linear route (CHOLMOD, CG + Jacobi, CG + incomplete
// Cholesky), and records assembly, factorization and solve times, CG
// iterations, residuals and peak memory.
//
//   solvers_bench [--sizes 10000,50000,200000] [--out bench/results/solvers.txt]
//
// Each configuration runs in a child process (fork) so that its peak
// resident memory (ru_maxrss) is its own: the domain (built once by the
// parent) plus everything the solve allocates. Per configuration:
//   cold   - a fresh solver on the domain, no warm start;
//   refit  - the same solver object, same domain again (CHOLMOD reuses its
//            symbolic analysis; CG starts from the previous f);
//   warm   - the domain refined as the progressive loop does (5% more
//            vertices near the surface, f interpolated by Domain::insert),
//            solved with that f as warm start.
// The samples are an ellipsoid (1, 0.7, 0.5) with exact normals; the domain
// is Domain::initial plus two thirds of its vertices in a shell around the
// surface and one third spread through the ball, like a progressive domain.
#include <pdd/domain.h>
#include <pdd/solvers.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using pdd::Vec3;

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

// Points near the surface: samples moved along the normal and sideways.
std::vector<Vec3> shell_points(const pdd::PointSet& samples, int n, double width, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, static_cast<int>(samples.size()) - 1);
  std::normal_distribution<double> g(0.0, width);
  std::vector<Vec3> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    const int k = pick(rng);
    out.push_back(samples.points[k] + g(rng) * samples.normals[k] +
                  0.5 * Vec3(g(rng), g(rng), g(rng)));
  }
  return out;
}

pdd::Domain make_domain(const pdd::PointSet& samples, int target, std::mt19937& rng) {
  pdd::Domain domain = pdd::Domain::initial(samples);
  const int extra = std::max(0, target - static_cast<int>(domain.num_vertices()));
  std::vector<Vec3> points = shell_points(samples, 2 * extra / 3, 0.04, rng);
  const double r = 0.85 * domain.radius();
  std::uniform_real_distribution<double> u(-r, r);
  while (static_cast<int>(points.size()) < extra) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.norm() < r) points.push_back(domain.center() + p);
  }
  domain.insert(points);
  return domain;
}

struct Config {
  pdd::SolverKind kind;
  pdd::LinearMethod method;
  pdd::Preconditioner preconditioner;
  const char* route;
};

std::string run(const Config& c, const pdd::Domain& base, const pdd::PointSet& samples) {
  pdd::SolverOptions options;
  options.kind = c.kind;
  options.ssd.noise = pdd::estimate_noise(samples);  // once, as reconstruct() does
  options.linear.method = c.method;
  options.linear.preconditioner = c.preconditioner;
  std::ostringstream line;
  char buf[512];
  try {
    auto solver = pdd::make_solver(options);
    const std::vector<double> f = solver->solve(base, samples);
    const pdd::SolverStats cold = solver->stats();
    solver->solve(base, samples, &f);
    const pdd::SolverStats refit = solver->stats();
    pdd::Domain refined = base;
    refined.set_f(f);
    std::mt19937 rng(99);
    refined.insert(shell_points(samples, static_cast<int>(base.num_vertices() / 20), 0.04, rng));
    const std::vector<double> warm_start = refined.f();
    solver->solve(refined, samples, &warm_start);
    const pdd::SolverStats warm = solver->stats();
    std::snprintf(buf, sizeof buf,
                  "%-9s %-10s %8.3f %8.3f %8.3f %6d %9.1e %10zu | %8.3f %8.3f %6d | %8.3f %6d",
                  pdd::to_string(c.kind).c_str(), c.route, cold.assembly_seconds,
                  cold.factorize_seconds, cold.solve_seconds, cold.iterations, cold.residual,
                  cold.nonzeros, refit.factorize_seconds, refit.solve_seconds, refit.iterations,
                  warm.factorize_seconds + warm.solve_seconds, warm.iterations);
    line << buf;
  } catch (const std::exception& e) {
    std::snprintf(buf, sizeof buf, "%-9s %-10s FAILED: ", pdd::to_string(c.kind).c_str(), c.route);
    line << buf << e.what();
  }
  return line.str();
}

// Runs `c` in a child process; returns its line and peak memory.
std::string run_isolated(const Config& c, const pdd::Domain& domain, const pdd::PointSet& samples) {
  int fd[2];
  if (pipe(fd) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    const std::string line = run(c, domain, samples);
    if (write(fd[1], line.data(), line.size()) < 0) _exit(1);
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
  if (line.empty()) line = std::string(pdd::to_string(c.kind)) + " " + c.route + " CRASHED";
  char mem[64];
  std::snprintf(mem, sizeof mem, " | %7.0f", usage.ru_maxrss / 1024.0);
  return line + mem;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {10000, 50000, 200000};
  std::string out_path = "bench/results/solvers.txt";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream ss(argv[i + 1]);
      std::string item;
      while (std::getline(ss, item, ',')) sizes.push_back(std::stoi(item));
    } else if (!std::strcmp(argv[i], "--out")) {
      out_path = argv[i + 1];
    }
  }
  using K = pdd::SolverKind;
  using M = pdd::LinearMethod;
  using P = pdd::Preconditioner;
  const std::vector<Config> configs = {
      {K::kPoisson, M::kCholmod, P::kAuto, "cholmod"},
      {K::kPoisson, M::kConjugateGradient, P::kJacobi, "cg+jacobi"},
      {K::kPoisson, M::kConjugateGradient, P::kIncompleteCholesky, "cg+ic"},
      {K::kSsd, M::kCholmod, P::kAuto, "cholmod"},
      {K::kSsd, M::kConjugateGradient, P::kJacobi, "cg+jacobi"},
      {K::kSsd, M::kConjugateGradient, P::kIncompleteCholesky, "cg+ic"},
      {K::kSpectral, M::kCholmod, P::kAuto, "cholmod"},
      {K::kSpectral, M::kConjugateGradient, P::kIncompleteCholesky, "cg+ic"},
  };

  std::ostringstream report;
  report << "# solvers_bench: ellipsoid samples, domain = initial + shell + uniform points\n"
         << "# times in seconds (wall), memory = peak RSS of the configuration's process in MB\n"
         << "# columns: solver route assembly factorize solve iterations residual nnz"
         << " | refit: factorize solve iterations | warm (5% refined): factorize+solve iterations"
         << " | peak MB\n";
  std::cout << report.str();
  for (int target : sizes) {
    std::mt19937 rng(7);
    const pdd::PointSet samples = ellipsoid_samples(std::max(2000, target / 4));
    const auto start = std::chrono::steady_clock::now();
    const pdd::Domain domain = make_domain(samples, target, rng);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream head;
    head << "\n## " << domain.num_vertices() << " vertices, " << domain.num_tets() << " tets, "
         << samples.size() << " samples (domain built in " << seconds << " s)\n";
    std::cout << head.str() << std::flush;
    report << head.str();
    for (const Config& c : configs) {
      // Slow routes that never won at smaller sizes are skipped where they
      // would take many minutes: the spectral solver with CG inner solves
      // (one solve per Lanczos step; 12 s at 10k, over 12 min at 50k) and
      // SSD with CG + Jacobi (4000+ iterations at 50k).
      if (c.kind == K::kSpectral && c.method == M::kConjugateGradient && target > 20000) continue;
      if (c.kind == K::kSsd && c.preconditioner == P::kJacobi && target > 60000) continue;
      const std::string line = run_isolated(c, domain, samples);
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
