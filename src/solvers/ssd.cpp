// Smooth signed distance reconstruction [CT11] on the domain, Eq. (15).
#include "solvers/kinds.h"
#include "solvers/linear_solver.h"
#include "solvers/problem.h"

#include "common/cancellation.h"
#include "common/parallel_kernels.h"

#include <pdd/errors.h>

namespace pdd::detail {
namespace {

const char* const kWhyNormals = "the SSD solver fits the gradient of f to oriented normals (Eq. 15)";

// The options with alpha = 0 replaced by ssd_value_weight for the samples.
SsdOptions resolved(SsdOptions options, const Problem& p, const PointSet& points) {
  if (options.alpha > 0) return options;
  const double noise = options.noise >= 0 ? options.noise : estimate_noise(points);
  options.alpha = ssd_value_weight(noise, p.length);
  return options;
}

// The system A f = b of Eq. (15) for a located problem, A whole or its lower
// triangle (the solver's: half the memory of the solve's largest matrix).
LinearSystem ssd_system(const Problem& p, const SsdOptions& options, Stored stored) {
  const bool lower = stored == Stored::kLower;
  const double nx = static_cast<double>(p.num_points);
  const double beta = options.beta / nx;
  const double alpha = options.alpha / (p.length * p.length * nx);

  // Eq. (15) in units of l: f(p) is a length (1/l^2) and the Hessian an
  // inverse length (l^2); |T| is the volume of the domain, as in CT11. The
  // two-ring Hessian term first, with nothing else of the system held (it is
  // the solve's peak of memory); the one-ring terms are then added into it.
  SparseMatrix A;
  if (options.gamma > 0) {
    hessian_energy(p.mesh, stored).swap(A);  // Eigen 3.4's SparseMatrix has no move: = would copy
    poll();
    A *= options.gamma * p.length * p.length / tet_volumes(p.mesh).sum();  // H^T M~_V^-1 H
  } else {
    // No Hessian term: the one-ring pattern, zero, to take the samples' terms.
    SparseMatrix pattern = cotangent_laplacian(p.mesh);
    if (lower) SparseMatrix(pattern.triangularView<Eigen::Lower>()).swap(pattern);
    pattern.makeCompressed();
    pattern.coeffs().setZero();
    A.swap(pattern);
  }
  poll();
  // S^T S counts the samples in each tet and S^T N sums their normals, so
  // G^T S^T S G = G^T diag(count_t I) G and G^T S^T N = G^T (sum of n_p per tet),
  // summed with Phi^T Phi from the samples' tets alone into A's pattern.
  Eigen::VectorXd b = beta * add_sample_terms(A, p.mesh, p.locations, p.normals, beta, alpha, stored);
  poll();
  LinearSystem system;
  system.A.swap(A);
  system.b = std::move(b);
  return system;
}

class SsdSolver final : public ImplicitSolver {
 public:
  SsdSolver(const SsdOptions& options, const LinearSolverOptions& linear)
      : options_(options), linear_(linear) {
    if (!(options.alpha >= 0) || !(options.beta > 0) || !(options.gamma >= 0))
      throw InputError(
          "SSD solver: alpha must be >= 0 (0: from the noise), beta > 0 and gamma >= 0");
  }

  std::vector<double> solve(const Domain& domain, const PointSet& points,
                            const std::vector<double>* warm_start) override {
    const auto start = Clock::now();
    stats_ = SolverStats();
    Problem p = make_problem(domain, points, "SSD solver", kWhyNormals,
                             {take_release_triangulation(), SamplingMatrix::kSkip, &order_,
                              linear_.iterative(domain.num_vertices())});
    const SsdOptions options = resolved(options_, p, points);
    const LinearSystem system = ssd_system(p, options, Stored::kLower);
    p.release_samples();
    p.release_ordered_tets();
    const SparseMatrix& A = system.A;
    const Eigen::VectorXd& b = system.b;
    stats_.assembly_seconds = seconds_since(start);

    linear_.compute(A, p.mesh.vertices, Stored::kLower, p.original);
    const auto solve_start = Clock::now();
    Eigen::VectorXd f = p.warm_start(warm_start);
    linear_.solve(b, f);
    stats_.solve_seconds = seconds_since(solve_start);

    linear_.report(stats_);
    linear_.release();
    stats_.num_vertices = p.mesh.vertices.size();
    stats_.num_points = p.num_points;
    stats_.nonzeros = static_cast<std::size_t>(2 * A.nonZeros() - A.rows());  // both triangles
    stats_.value_weight = options.alpha;
    return p.domain_values(f);
  }

  const SolverStats& stats() const override { return stats_; }
  bool needs_normals() const override { return true; }
  bool needs_oriented_normals() const override { return true; }

 private:
  SsdOptions options_;
  LinearSolver linear_;
  SolverStats stats_;
  SampleOrder order_;
};

}  // namespace

}  // namespace pdd::detail

namespace pdd {

LinearSystem ssd_system(const Domain& domain, const PointSet& points, const SsdOptions& options) {
  const detail::Problem p = detail::make_problem(domain, points, "SSD system", detail::kWhyNormals,
                                                 {false, detail::SamplingMatrix::kSkip, nullptr});
  return detail::ssd_system(p, detail::resolved(options, p, points), Stored::kAll);
}

}  // namespace pdd

namespace pdd::detail {

std::unique_ptr<ImplicitSolver> make_ssd_solver(const SsdOptions& options,
                                                const LinearSolverOptions& linear) {
  return std::make_unique<SsdSolver>(options, linear);
}

}  // namespace pdd::detail
