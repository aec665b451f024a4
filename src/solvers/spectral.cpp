// Spectral reconstruction [ACTD07] on the domain, Eqs. (16)-(17): the
// generalized eigenvector of the largest eigenvalue, by Spectra's Lanczos
// iteration on B^-1 A with B factorized once.
#include "solvers/kinds.h"
#include "solvers/linear_solver.h"
#include "solvers/problem.h"

#include <pdd/errors.h>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>

#include <sstream>

namespace pdd::detail {
namespace {

// Spectra's "B operation" for GEigsMode::RegularInverse: products with B and
// solves with B, the latter through our LinearSolver.
class ConstraintOperator {
 public:
  using Scalar = double;
  ConstraintOperator(const SparseMatrix& B, LinearSolver& solver) : B_(B), solver_(solver) {}
  Eigen::Index rows() const { return B_.rows(); }
  void solve(const double* x_in, double* y_out) const {
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x_in, B_.rows());
    Eigen::VectorXd y(B_.rows());
    y.setZero();
    solver_.solve(x, y);
    Eigen::Map<Eigen::VectorXd>(y_out, B_.rows()) = y;
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<Eigen::VectorXd>(y_out, B_.rows()) =
        B_ * Eigen::Map<const Eigen::VectorXd>(x_in, B_.rows());
  }

 private:
  const SparseMatrix& B_;
  LinearSolver& solver_;
};

class SpectralSolver final : public ImplicitSolver {
 public:
  SpectralSolver(const SpectralOptions& options, const LinearSolverOptions& linear)
      : options_(options),
        linear_(linear) {
    if (!(options.alpha > 0) || !(options.beta >= 0) || !(options.gamma >= 0) ||
        !(options.mu >= 0))
      throw InputError("spectral solver: alpha must be > 0 and beta, gamma, mu >= 0");
    if (options.krylov_size < 3 || options.max_restarts < 1 || !(options.tolerance > 0))
      throw InputError("spectral solver: krylov size must be >= 3, restarts >= 1, tolerance > 0");
  }

  std::vector<double> solve(const Domain& domain, const PointSet& points,
                            const std::vector<double>* warm_start) override {
    const auto start = Clock::now();
    stats_ = SolverStats();
    const Problem p =
        make_problem(domain, points, "spectral solver",
                     "the spectral solver needs normals, oriented or not (Eq. 16)");
    const double nx = static_cast<double>(p.num_points);
    const std::size_t nt = p.mesh.tets.size();

    // Left side of Eq. (17): G^T S^T C S G, with C_p = I + mu n_p n_p^T
    // (invariant under n_p -> -n_p), each sample's term weighted by the
    // volume of its tet over the mean of those volumes. The weight makes the
    // sum the domain integral of grad f^T C grad f that ACTD07 maximizes, with
    // C concentrated in the samples' tets; on a uniform mesh it is Eq. (17)
    // as printed. Without it a sliver holding a sample has an unbounded
    // gradient at a bounded cost in B, and the top eigenvector is a dipole
    // across that sliver (measured on the torus of the tests: the zero set
    // was off by 1.1 instead of 0.004).
    const Eigen::VectorXd volume = tet_volumes(p.mesh);
    double mean_volume = 0;
    for (const Location& l : p.locations) mean_volume += volume[l.tet];
    mean_volume /= nx;
    std::vector<Eigen::Matrix3d> tensor(nt, Eigen::Matrix3d::Zero());
    for (std::size_t i = 0; i < p.num_points; ++i) {
      const int t = p.locations[i].tet;
      tensor[t] += (volume[t] / mean_volume) *
                   (Eigen::Matrix3d::Identity() + options_.mu * p.normals[i] * p.normals[i].transpose());
    }
    const SparseMatrix A = weighted_stiffness(p.mesh, tensor);

    // Right side of Eq. (17), in units of l: alpha/|X| Phi^T Phi + beta L / l
    // + gamma l L M_V^-1 L (B = L M_V^-1 L is the bi-Laplacian).
    SparseMatrix B = (options_.alpha / nx) * gram_matrix(p.Phi, Eigen::VectorXd::Ones(p.Phi.rows()));
    if (options_.beta > 0 || options_.gamma > 0) {
      const SparseMatrix L = cotangent_laplacian(p.mesh);
      if (options_.beta > 0) B += (options_.beta / p.length) * L;
      if (options_.gamma > 0) {
        // L is symmetric, so L M_V^-1 L = L^T M_V^-1 L.
        B += (options_.gamma * p.length) * gram_matrix(L, vertex_masses(p.mesh).cwiseInverse());
      }
    }
    stats_.assembly_seconds = seconds_since(start);

    linear_.compute(B, p.mesh.vertices);
    const auto solve_start = Clock::now();
    Spectra::SparseSymMatProd<double> a_op(A);
    ConstraintOperator b_op(B, linear_);
    const Eigen::Index n = B.rows();
    const Eigen::Index ncv = std::min<Eigen::Index>(options_.krylov_size, n);
    Spectra::SymGEigsSolver<Spectra::SparseSymMatProd<double>, ConstraintOperator,
                            Spectra::GEigsMode::RegularInverse>
        eigs(a_op, b_op, 1, ncv);
    // The warm start is checked but not used: from Spectra's own (fixed-seed,
    // deterministic) start vector Lanczos converges in one restart, while
    // starting from the previous eigenvector took 22 restarts and 20x longer
    // (measured, bench/solvers_bench.cpp, 10k vertices).
    warm_start_vector(warm_start, p.mesh.vertices.size());
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, options_.max_restarts, options_.tolerance);
    stats_.iterations = static_cast<int>(eigs.num_operations());
    if (eigs.info() != Spectra::CompInfo::Successful) {
      std::ostringstream msg;
      msg << "spectral solver: Lanczos did not converge in " << eigs.num_iterations()
          << " restarts (" << stats_.iterations << " solves with B)";
      throw SolverError(msg.str());
    }
    const double lambda = eigs.eigenvalues()[0];
    Eigen::VectorXd f = eigs.eigenvectors().col(0);
    const Eigen::VectorXd Bf = B * f;
    stats_.residual = (A * f - lambda * Bf).norm() / (std::abs(lambda) * Bf.norm());
    if (!f.allFinite() || !(lambda > 0)) {
      std::ostringstream msg;
      msg << "spectral solver: no positive eigenvalue (lambda = " << lambda
          << ", relative residual " << stats_.residual << ")";
      throw SolverError(msg.str());
    }

    // Sign: f > 0 on the boundary of the domain, measured from the isovalue.
    const double iso = median_at_samples(p.Phi, f);
    double outside = 0;
    const std::vector<int> outer = outer_vertices(domain);
    for (int v : outer) outside += f[v] - iso;
    if (outside < 0) f = -f;
    if (options_.median_shift) {
      stats_.median_shift = median_at_samples(p.Phi, f);
      f.array() -= stats_.median_shift;
    }
    stats_.solve_seconds = seconds_since(solve_start);

    stats_.method = std::string("lanczos+") + linear_.method_name();
    stats_.eigenvalue = lambda;
    stats_.factorize_seconds = linear_.setup_seconds();
    stats_.levels = linear_.levels();
    linear_.release();
    stats_.num_vertices = p.mesh.vertices.size();
    stats_.num_points = p.num_points;
    stats_.nonzeros = static_cast<std::size_t>(B.nonZeros());
    return to_std(f);
  }

  const SolverStats& stats() const override { return stats_; }
  bool needs_normals() const override { return true; }
  bool needs_oriented_normals() const override { return false; }

 private:
  SpectralOptions options_;
  LinearSolver linear_;
  SolverStats stats_;
};

}  // namespace

std::unique_ptr<ImplicitSolver> make_spectral_solver(const SpectralOptions& options,
                                                     const LinearSolverOptions& linear) {
  return std::make_unique<SpectralSolver>(options, linear);
}

}  // namespace pdd::detail
