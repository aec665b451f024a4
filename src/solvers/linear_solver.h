// Private to src/solvers: the symmetric positive definite solve behind every
// solver, by CHOLMOD (supernodal Cholesky with OpenBLAS) or by conjugate
// gradients (Jacobi or incomplete Cholesky preconditioner) with a warm start.
#pragma once

#include <pdd/fem.h>
#include <pdd/solvers.h>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace pdd::detail {

// A linear route with kAuto resolved.
struct LinearRoute {
  LinearMethod method = LinearMethod::kCholmod;               // kCholmod or kConjugateGradient
  Preconditioner preconditioner = Preconditioner::kJacobi;   // kJacobi or kIncompleteCholesky
  // kConjugateGradient only, when > 0 (LinearMethod::kAuto): CHOLMOD solves
  // instead when there is no warm start, or once CG has run this many
  // iterations without converging.
  int cholmod_after = 0;
};

class LinearSolver {
 public:
  LinearSolver(const LinearSolverOptions& options, const LinearRoute& route);
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  // Prepares solves with the SPD matrix A (all entries stored; CHOLMOD reads
  // the lower triangle): CHOLMOD factorizes, reusing the symbolic analysis
  // of the previous matrix when the sparsity pattern is the same; CG builds
  // its preconditioner (with LinearRoute::cholmod_after, the first solve()
  // builds what it needs instead). A is not copied: it must stay alive and unchanged
  // until the last solve() with it. Throws SolverError when the
  // factorization fails (A not positive definite numerically). The
  // incomplete Cholesky preconditioner orders the unknowns by AMD on
  // ordering_pattern when given (a sparser matrix with A's graph at its
  // core, e.g. the one-ring pattern of a two-ring system: 5x cheaper to
  // order, as good an ordering), else on A; it must outlive the solves too.
  void compute(const SparseMatrix& A, const SparseMatrix* ordering_pattern = nullptr);

  // Solves A x = b. On entry x is a warm start for CG (empty or zero means
  // none); CHOLMOD ignores it. Throws SolverError, naming the relative residual,
  // when CG does not reach its tolerance, a direct solve's residual exceeds
  // options.max_residual or the result is not finite.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  // Of the last solve: "cholmod", "cg+jacobi" or "cg+ic", or "cg+..., then
  // cholmod" when CG gave up (LinearRoute::cholmod_after).
  const std::string& method_name() const { return method_; }
  int iterations() const { return iterations_; }  // of the last solve (0 for CHOLMOD)
  double residual() const { return residual_; }   // |A x - b| / |b| of the last solve
  // Of the last compute() and of the factorization or preconditioner that
  // solve() built for it (LinearRoute::cholmod_after), which alone
  // factorize_seconds_in_solves() counts.
  double factorize_seconds() const { return factorize_seconds_; }
  double factorize_seconds_in_solves() const { return factorize_seconds_in_solves_; }
  bool reused_analysis() const { return reused_analysis_; }        // last compute() kept the analysis
  double ic_shift() const { return ic_shift_; }  // of the last solve by cg+ic, else 0

  // Copies the above into stats (method, iterations, residual,
  // factorize_seconds, reused_analysis).
  void report(SolverStats& stats) const {
    stats.method = method_name();
    stats.iterations = iterations_;
    stats.residual = residual_;
    stats.factorize_seconds = factorize_seconds_;
    stats.reused_analysis = reused_analysis_;
    stats.ic_shift = ic_shift_;
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  LinearRoute route_;
  int iterations_ = 0;
  double residual_ = 0;
  double factorize_seconds_ = 0;
  double factorize_seconds_in_solves_ = 0;
  bool reused_analysis_ = false;
  double ic_shift_ = 0;
  std::string method_ = "none";
};

}  // namespace pdd::detail
