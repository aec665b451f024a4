// Screened Poisson reconstruction on the domain, Eqs. (13)-(14).
#include "solvers/kinds.h"
#include "solvers/linear_solver.h"
#include "solvers/normal_field.h"
#include "solvers/problem.h"

#include "common/cancellation.h"
#include "common/parallel_kernels.h"

#include <pdd/errors.h>

namespace pdd::detail {
namespace {

class PoissonSolver final : public ImplicitSolver {
 public:
  PoissonSolver(const PoissonOptions& options, const LinearSolverOptions& linear)
      : options_(options), linear_(linear) {
    if (!(options.alpha >= 0))
      throw InputError("Poisson solver: alpha must be >= 0 (0: from the noise)");
    if (!(options.kernel_size >= 0)) throw InputError("Poisson solver: kernel size must be >= 0");
    if (options.kernel_size == 0 && !(options.kernel_spacing > 0))
      throw InputError("Poisson solver: kernel spacing must be > 0");
  }

  std::vector<double> solve(const Domain& domain, const PointSet& points,
                            const std::vector<double>* warm_start) override {
    const auto start = Clock::now();
    stats_ = SolverStats();
    const Problem p = make_problem(domain, points, "Poisson solver",
                                   "the Poisson solver needs oriented normals (Eq. 13)",
                                   {take_release_triangulation(), SamplingMatrix::kBuild, &order_,
                                    linear_.iterative(domain.num_vertices())});
    const NearestNeighbors tree(points.points);  // the samples' one tree for the three below
    const double sigma = options_.kernel_size > 0
                             ? options_.kernel_size
                             : options_.kernel_spacing * mean_spacing(points.points, tree);
    if (!(sigma > 0)) throw InputError("Poisson solver: the normal kernel size is zero");

    // Right-hand side Div N~ := G^T M_T n~, the integrated divergence (with
    // the sign that makes Eq. (14) the normal equations of Eq. (13)).
    std::vector<Vec3> normals = p.normals;
    const std::vector<double> weight = density_weights(points.points, tree, sigma);
    for (std::size_t i = 0; i < normals.size(); ++i) normals[i] *= weight[i];
    const std::vector<Vec3> field =
        smoothed_normal_field(p.mesh, points.points, tree, normals, sigma);
    const Eigen::VectorXd volume = tet_volumes(p.mesh);
    std::vector<Vec3> weighted(field.size());
    for (std::size_t t = 0; t < field.size(); ++t) weighted[t] = volume[static_cast<Eigen::Index>(t)] * field[t];
    const Eigen::VectorXd b = gradient_transpose_times(p.mesh, weighted);

    // Eq. (14) in units of l: [L + alpha l / |X| Phi^T Phi] F = Div N~.
    SparseMatrix A = cotangent_laplacian(p.mesh);
    const double l00 = A.coeff(0, 0);
    poll();
    if (options_.screened) {
      double alpha = options_.alpha;
      if (alpha == 0)
        alpha = ssd_value_weight(options_.noise >= 0 ? options_.noise : estimate_noise(points),
                                 p.length);
      stats_.value_weight = alpha;
      const double w = alpha * p.length / static_cast<double>(p.num_points);
      const SparseMatrix values = gram_matrix(p.Phi, Eigen::VectorXd::Ones(p.Phi.rows()));
      add_to(A, values, w);
    } else {
      // The original Poisson equation: f is defined up to a constant, fixed
      // by the penalty L_00 f_0^2, which does not change the minimizers of
      // Eq. (13) other than selecting f_0 = 0.
      A.coeffRef(0, 0) += l00;
    }
    stats_.assembly_seconds = seconds_since(start);

    linear_.compute(A, p.mesh.vertices, Stored::kAll, p.original);
    const auto solve_start = Clock::now();
    Eigen::VectorXd f = p.warm_start(warm_start);
    linear_.solve(b, f);
    if (options_.median_shift) {
      stats_.median_shift = median_at_samples(p.Phi, f);
      f.array() -= stats_.median_shift;
    }
    stats_.solve_seconds = seconds_since(solve_start);

    linear_.report(stats_);
    linear_.release();
    stats_.num_vertices = p.mesh.vertices.size();
    stats_.num_points = p.num_points;
    stats_.nonzeros = static_cast<std::size_t>(A.nonZeros());
    stats_.kernel_size = sigma;
    return p.domain_values(f);
  }

  const SolverStats& stats() const override { return stats_; }
  bool needs_normals() const override { return true; }
  bool needs_oriented_normals() const override { return true; }

 private:
  PoissonOptions options_;
  LinearSolver linear_;
  SolverStats stats_;
  SampleOrder order_;
};

}  // namespace

std::unique_ptr<ImplicitSolver> make_poisson_solver(const PoissonOptions& options,
                                                    const LinearSolverOptions& linear) {
  return std::make_unique<PoissonSolver>(options, linear);
}

}  // namespace pdd::detail
