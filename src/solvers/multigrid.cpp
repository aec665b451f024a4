#include "solvers/multigrid.h"

#include "common/conjugate_gradient.h"
#include "common/parallel_kernels.h"
#include "solvers/block_jacobi.h"

#include <pdd/errors.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pdd::detail {
namespace {

SparseMatrix compressed_transpose(const SparseMatrix& M) {
  SparseMatrix t = M.transpose();
  t.makeCompressed();
  return t;
}

// The largest eigenvalue of D^-1 A (A symmetric positive definite, D = L L^T
// the smoother's block diagonal) from `steps` Lanczos steps on L^-1 A L^-T,
// which has its spectrum, from a fixed start.
template <class Product>
double largest_eigenvalue(Eigen::Index n, const Product& multiply, const BlockJacobi& D,
                          int steps) {
  steps = static_cast<int>(std::min<Eigen::Index>(steps, n));
  Eigen::VectorXd v(n), previous = Eigen::VectorXd::Zero(n), w(n), scaled(n), scaled_product(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i));
  v /= std::sqrt(deterministic_dot(v, v));
  std::vector<double> alpha, beta;
  double b = 0;
  for (int k = 0; k < steps; ++k) {
    D.apply_inverse_factor_transpose(v, scaled);
    multiply(scaled, scaled_product);
    D.apply_inverse_factor(scaled_product, w);
    const double a = deterministic_dot(w, v);
    alpha.push_back(a);
    w -= a * v + b * previous;
    b = std::sqrt(deterministic_dot(w, w));
    if (!(b > 1e-14 * std::abs(a))) break;
    beta.push_back(b);
    previous = v;
    v = w / b;
    poll();  // the run's cancellation: a product takes a fraction of a second at 1M
  }
  const int m = static_cast<int>(alpha.size());
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
  for (int k = 0; k < m; ++k) {
    T(k, k) = alpha[k];
    if (k + 1 < m) T(k, k + 1) = T(k + 1, k) = beta[k];
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

}  // namespace

struct Multigrid::Impl {
  struct Level {
    // The level's matrix: level 0's is the caller's; a coarse level's is
    // P^T A P of the finer one, its lower triangle, in single precision but
    // on the coarsest level (factored by CHOLMOD): it only enters the
    // V-cycle, whose products sum in double.
    const SparseMatrix* A = nullptr;  // level 0 and the coarsest
    const SymmetricProduct<double>* times_A = nullptr;  // level 0's: the caller's
    SparseMatrix coarsest;
    Eigen::SparseMatrix<float> single;  // the others
    SymmetricProduct<float> times_single;
    const SparseMatrix* P = nullptr;    // to this level from the next coarser one
    SparseMatrix R;                     // P^T, stored by columns: the rows of P
    BlockJacobi smoother;               // D, the diagonal with blocks of strongly coupled unknowns
    double largest = 0;                 // of D^-1 A, a bound from Lanczos
    int degree = 0;                     // of the smoothing polynomial
    // Work vectors (the V-cycle is const but reuses them: one at a time).
    mutable Eigen::VectorXd residual, correction, direction, product, scaled, coarse_rhs, coarse_x;

    void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
      if (times_A)
        (*times_A)(x, y);
      else if (A)  // the coarsest is solved by CHOLMOD, not smoothed
        throw std::logic_error("multigrid: a product with the coarsest level");
      else
        times_single(x, y);
    }
    Eigen::Index size() const { return A ? A->rows() : single.rows(); }
    // Both triangles counted.
    Eigen::Index nonzeros() const {
      return times_A ? times_A->nonzeros()
                     : 2 * (A ? A->nonZeros() : single.nonZeros()) - size();
    }
  };
  MultigridOptions options;
  std::vector<Level> levels;
  std::unique_ptr<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>> coarsest;

  // Smoothing of A x = b from x: the fourth-kind Chebyshev polynomial in
  // D^-1 A of Lottes (2023, "Optimal polynomial smoothers for multigrid
  // V-cycles", Alg. 3), which needs only the largest eigenvalue, D the
  // level's block Jacobi (block_jacobi.h). From x = 0 when zero_start (no
  // product for the first residual).
  void smooth(const Level& l, const Eigen::VectorXd& b, Eigen::VectorXd& x,
              bool zero_start) const {
    const double rho = l.largest;
    Eigen::VectorXd& r = l.residual;
    Eigen::VectorXd& d = l.direction;
    Eigen::VectorXd& q = l.product;
    Eigen::VectorXd& z = l.scaled;
    const Eigen::Index n = b.size();
    if (zero_start)
      r = b;
    else {
      l.multiply(x, q);
      r = b - q;
    }
    l.smoother.apply_inverse(r, z);
    d.resize(n);
    for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i) {
        d[i] = (4.0 / 3.0) / rho * z[i];
        x[i] += d[i];
      }
    });
    for (int k = 1; k < l.degree; ++k) {
      poll();  // the run's cancellation, inside a CG iteration (seconds at 1M)
      l.multiply(d, q);
      const double c1 = (2.0 * k - 1) / (2.0 * k + 3), c2 = (8.0 * k + 4) / (2.0 * k + 3) / rho;
      r -= q;
      l.smoother.apply_inverse(r, z);
      for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
        for (Eigen::Index i = begin; i < end; ++i) {
          d[i] = c1 * d[i] + c2 * z[i];
          x[i] += d[i];
        }
      });
    }
  }

  // x = V-cycle(b) on level k, from zero.
  void vcycle(std::size_t k, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    const Level& l = levels[k];
    if (k + 1 == levels.size()) {
      x = coarsest->solve(b);
      return;
    }
    x.setZero(b.size());
    smooth(l, b, x, /*zero_start=*/true);
    // Restrict the residual, correct from the coarser level, smooth again.
    const Level& c = levels[k + 1];
    Eigen::VectorXd& r = l.residual;
    l.multiply(x, l.product);
    r = b - l.product;
    transposed_product(*c.P, r, c.coarse_rhs);
    vcycle(k + 1, c.coarse_rhs, c.coarse_x);
    transposed_product(c.R, c.coarse_x, l.correction);
    x += l.correction;
    smooth(l, b, x, /*zero_start=*/false);
  }
};

Multigrid::Multigrid() : impl_(std::make_unique<Impl>()) {}
Multigrid::~Multigrid() = default;
Multigrid::Multigrid(Multigrid&&) noexcept = default;
Multigrid& Multigrid::operator=(Multigrid&&) noexcept = default;

void Multigrid::setup(const SymmetricProduct<double>& times_A,
                      const std::vector<SparseMatrix>& prolongations,
                      const MultigridOptions& options) {
  const SparseMatrix& A = times_A.matrix();
  const Stored stored = times_A.lower() ? Stored::kLower : Stored::kAll;
  Impl& d = *impl_;
  d.options = options;
  d.levels.clear();
  d.levels.reserve(prolongations.size() + 1);
  d.levels.resize(1);
  d.levels[0].A = &A;
  d.levels[0].times_A = &times_A;
  // The smoother's blocks and bound of each level but the coarsest (a lower
  // triangle gives BlockJacobi all it reads: the entries below the diagonal).
  auto finish = [&](Impl::Level& l, const auto& matrix) {
    l.degree = &l == &d.levels[0] ? options.finest_smoothing_degree : options.smoothing_degree;
    l.smoother = BlockJacobi(matrix, options.block_coupling, options.max_block);
    poll();
    // Lanczos' estimate lies below the true value: a margin of 10 %.
    l.largest = 1.1 * largest_eigenvalue(
                          l.size(), [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
                            l.multiply(x, y);
                          },
                          l.smoother, 12);
    l.smoother.invert();
    poll();
  };
  auto coarsest = [&](std::size_t k, Eigen::Index size) {
    return k == prolongations.size() || size <= static_cast<Eigen::Index>(options.coarsest_size);
  };
  if (!coarsest(0, A.rows())) finish(d.levels[0], A);
  for (std::size_t k = 0; !coarsest(k, d.levels[k].size()); ++k) {
    const SparseMatrix& P = prolongations[k];
    const Impl::Level& fine = d.levels[k];
    if (P.rows() != fine.size())
      throw std::invalid_argument("multigrid: a prolongation does not match its fine level");
    // Built in place (the levels are reserved, so `fine` stays valid), and
    // swapped in: Eigen 3.4's SparseMatrix has no move, = and push_back copy.
    Impl::Level& coarse = d.levels.emplace_back();
    coarse.P = &P;
    compressed_transpose(P).swap(coarse.R);
    // The coarse levels hold their lower triangles (half the memory), whatever A's storage.
    const Stored fine_stored = k == 0 ? stored : Stored::kLower;
    constexpr Stored lower = Stored::kLower;
    if (coarsest(k + 1, P.cols())) {
      (fine.A ? galerkin_product(P, *fine.A, fine_stored, lower)
              : galerkin_product(P, fine.single, fine_stored, lower))
          .swap(coarse.coarsest);
      coarse.A = &coarse.coarsest;
    } else {
      (fine.A ? galerkin_product<float>(P, *fine.A, fine_stored, lower)
              : galerkin_product<float>(P, fine.single, fine_stored, lower))
          .swap(coarse.single);
      coarse.times_single = SymmetricProduct<float>(coarse.single, /*lower=*/true);
      finish(coarse, coarse.single);
    }
    poll();
  }
  d.coarsest = std::make_unique<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>();
  d.coarsest->cholmod().print = 0;
  d.coarsest->compute(*d.levels.back().A);
  if (d.coarsest->info() != Eigen::Success)
    throw SolverError("multigrid: the coarsest level (" +
                      std::to_string(d.levels.back().A->rows()) +
                      " unknowns) is not positive definite");
}

void Multigrid::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  impl_->vcycle(0, r, z);
}

void Multigrid::clear() {
  impl_->levels.clear();
  impl_->levels.shrink_to_fit();
  impl_->coarsest.reset();
}

std::size_t Multigrid::num_levels() const { return impl_->levels.size(); }
std::size_t Multigrid::level_size(std::size_t level) const {
  return static_cast<std::size_t>(impl_->levels.at(level).size());
}
std::size_t Multigrid::level_nonzeros(std::size_t level) const {
  return static_cast<std::size_t>(impl_->levels.at(level).nonzeros());
}

CgResult multigrid_cg(const SymmetricProduct<double>& A, const Multigrid& M,
                      const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                      int max_iterations) {
  CgResult result;
  const Eigen::Index n = b.size();
  const double b_norm = std::sqrt(deterministic_dot(b, b));
  if (x.size() != n) x.setZero(n);
  if (b_norm == 0) {
    x.setZero(n);
    result.converged = true;
    return result;
  }
  Eigen::VectorXd r(n), q(n);
  A(x, q);
  r = b - q;
  const PcgResult cg = preconditioned_cg(
      [&](const Eigen::VectorXd& p, Eigen::VectorXd& Ap) { A(p, Ap); },
      [&](const Eigen::VectorXd& residual, Eigen::VectorXd& z) { M.precondition(residual, z); },
      r, x, tolerance, b_norm, max_iterations);
  result.iterations = cg.iterations;
  result.converged = cg.converged;
  // The recursive residual drifts from the true one over many iterations.
  A(x, q);
  result.residual = std::sqrt(deterministic_dot(b - q, b - q)) / b_norm;
  if (result.converged && result.residual > 10 * tolerance) result.converged = false;
  return result;
}

}  // namespace pdd::detail
