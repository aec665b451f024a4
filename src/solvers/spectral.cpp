// Spectral reconstruction [ACTD07] on the domain, Eqs. (16)-(17): the
// generalized eigenvector of the largest eigenvalue, by LOBPCG preconditioned
// with the multigrid of B (lobpcg.h), started from the previous domain's f.
#include "solvers/kinds.h"
#include "solvers/linear_solver.h"
#include "solvers/lobpcg.h"
#include "solvers/problem.h"

#include "common/parallel_kernels.h"

#include <pdd/errors.h>
#include <pdd/sizing.h>

#include <sstream>

namespace pdd::detail {
namespace {

// sum (f_i - f_j)^2 over the edges of the domain's outer boundary (the
// faces of tets without a neighbour), each edge once per face it bounds.
SparseMatrix outer_boundary_laplacian(const Domain& domain) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto edge = [&](int u, int v) {
    entries.emplace_back(u, u, 1.0);
    entries.emplace_back(v, v, 1.0);
    entries.emplace_back(u, v, -1.0);
    entries.emplace_back(v, u, -1.0);
  };
  for_each_hull_face(domain, [&](int a, int b, int c) {
    edge(a, b);
    edge(b, c);
    edge(c, a);
  });
  const Eigen::Index n = static_cast<Eigen::Index>(domain.num_vertices());
  SparseMatrix T(n, n);
  T.setFromTriplets(entries.begin(), entries.end());
  return T;
}

// The tie's weight: outer_tie times the mean diagonal of B over the outer
// boundary's vertices, so that it is as strong as the rest of the
// constraint there whatever the input's scale and alpha.
double outer_tie_weight(const SparseMatrix& B, const SparseMatrix& T, double outer_tie) {
  double sum = 0;
  int count = 0;
  for (Eigen::Index v = 0; v < T.outerSize(); ++v)
    if (T.col(v).nonZeros() > 0) {
      sum += B.coeff(v, v);
      ++count;
    }
  return count > 0 ? outer_tie * sum / count : 0.0;
}

class SpectralSolver final : public ImplicitSolver {
 public:
  SpectralSolver(const SpectralOptions& options, const LinearSolverOptions& linear)
      : options_(options),
        linear_(linear) {
    if (!(options.alpha >= 0) || !(options.beta >= 0) || !(options.gamma >= 0) ||
        !(options.mu >= 0) || !(options.outer_tie >= 0))
      throw InputError(
          "spectral solver: alpha must be >= 0 (0: from the noise) and beta, gamma, mu and the "
          "outer tie >= 0");
    if (options.max_iterations < 1 || !(options.tolerance > 0))
      throw InputError("spectral solver: iterations must be >= 1 and the tolerance > 0");
  }

  std::vector<double> solve(const Domain& domain, const PointSet& points,
                            const std::vector<double>* warm_start) override {
    const auto start = Clock::now();
    stats_ = SolverStats();
    Problem p =
        make_problem(domain, points, "spectral solver",
                     "the spectral solver needs normals, oriented or not (Eq. 16)",
                     {take_release_triangulation(), SamplingMatrix::kBuild, &order_});
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
    // The per-tet tensors (72 bytes a tet) go once A is built.
    SparseMatrix A;
    {
      const Eigen::VectorXd volume = tet_volumes(p.mesh);
      double mean_volume = 0;
      for (const Location& l : p.locations) mean_volume += volume[l.tet];
      mean_volume /= nx;
      std::vector<Eigen::Matrix3d> tensor(nt, Eigen::Matrix3d::Zero());
      for (std::size_t i = 0; i < p.num_points; ++i) {
        const int t = p.locations[i].tet;
        tensor[t] += (volume[t] / mean_volume) *
                     (Eigen::Matrix3d::Identity() +
                      options_.mu * p.normals[i] * p.normals[i].transpose());
      }
      SparseMatrix(weighted_stiffness(p.mesh, tensor).triangularView<Eigen::Lower>()).swap(A);
    }
    // Phi stays for the isovalue at the end; the samples' locations and normals go.
    std::vector<Location>().swap(p.locations);
    std::vector<Vec3>().swap(p.normals);

    // Right side of Eq. (17), in units of l: alpha/|X| Phi^T Phi + beta L / l
    // + gamma l L M_V^-1 L (B = L M_V^-1 L is the bi-Laplacian), and the tie.
    const double alpha =
        options_.alpha > 0
            ? options_.alpha
            : spectral_value_weight(options_.noise >= 0 ? options_.noise : estimate_noise(points),
                                    options_.spacing >= 0 ? options_.spacing
                                                          : average_spacing(points),
                                    p.length);
    // The one-ring terms are added into the two-ring bi-Laplacian in place;
    // A and B are kept as their lower triangles (half the memory, as SSD's).
    SparseMatrix B;
    {
      const SparseMatrix values =
          gram_matrix(p.Phi, Eigen::VectorXd::Ones(p.Phi.rows()), Stored::kLower);
      if (options_.beta > 0 || options_.gamma > 0) {
        const SparseMatrix L = cotangent_laplacian(p.mesh);
        if (options_.gamma > 0) {
          // L is symmetric, so L M_V^-1 L = L^T M_V^-1 L.
          gram_matrix(L, vertex_masses(p.mesh).cwiseInverse(), Stored::kLower).swap(B);
          B *= options_.gamma * p.length;
          if (options_.beta > 0) add_to(B, L, options_.beta / p.length, true);
        } else {
          B = (options_.beta / p.length) * SparseMatrix(L.triangularView<Eigen::Lower>());
        }
        add_to(B, values, alpha / nx, true);
      } else {
        B = (alpha / nx) * values;
      }
    }
    if (options_.outer_tie > 0) {
      const SparseMatrix T = outer_boundary_laplacian(domain);
      add_to(B, T, outer_tie_weight(B, T, options_.outer_tie), true);
    }
    stats_.assembly_seconds = seconds_since(start);

    linear_.compute(B, p.mesh.vertices, Stored::kLower);
    const auto solve_start = Clock::now();
    Eigen::VectorXd f = p.warm_start(warm_start);
    const SymmetricProduct<double> a(A, true), b(B, true);
    const LobpcgResult eig = largest_eigenpair(
        a, b, [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { linear_.precondition(r, z); }, f,
        options_.tolerance, options_.max_iterations);
    stats_.iterations = eig.iterations;
    stats_.residual = eig.residual;
    const double lambda = eig.eigenvalue;
    if (!eig.converged) {
      std::ostringstream msg;
      msg << "spectral solver: LOBPCG did not converge in " << eig.iterations
          << " iterations (relative residual " << eig.residual << ")";
      throw SolverError(msg.str());
    }
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

    stats_.method = std::string("lobpcg+") + linear_.method_name();
    stats_.eigenvalue = lambda;
    stats_.factorize_seconds = linear_.setup_seconds();
    stats_.levels = linear_.levels();
    linear_.release();
    stats_.num_vertices = p.mesh.vertices.size();
    stats_.num_points = p.num_points;
    stats_.nonzeros = static_cast<std::size_t>(b.nonzeros());
    stats_.value_weight = alpha;
    return p.domain_values(f);
  }

  const SolverStats& stats() const override { return stats_; }
  bool needs_normals() const override { return true; }
  bool needs_oriented_normals() const override { return false; }

 private:
  SpectralOptions options_;
  LinearSolver linear_;
  SolverStats stats_;
  SampleOrder order_;
};

}  // namespace

std::unique_ptr<ImplicitSolver> make_spectral_solver(const SpectralOptions& options,
                                                     const LinearSolverOptions& linear) {
  return std::make_unique<SpectralSolver>(options, linear);
}

}  // namespace pdd::detail
