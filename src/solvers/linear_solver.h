// Private to src/solvers: the symmetric positive definite solve behind every
// solver: conjugate gradients preconditioned by multigrid V-cycles over the
// progressive hierarchy (multigrid.h, hierarchy.h), or CHOLMOD for small
// systems and LinearMethod::kCholmod.
#pragma once

#include <pdd/fem.h>
#include <pdd/solvers.h>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace pdd::detail {

class LinearSolver {
 public:
  explicit LinearSolver(const LinearSolverOptions& options);
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  // Prepares solves with the SPD matrix A (all entries stored, or its lower
  // triangle) of the domain whose vertices are `vertices` (one unknown per vertex): the
  // multigrid hierarchy and its Galerkin operators, or CHOLMOD's factor. A is
  // not copied: it must stay alive and unchanged until the last solve() with
  // it. Successive calls on domains each refined from the last use the
  // earlier ones as coarse levels. Throws SolverError when A is not positive
  // definite numerically.
  // Unknown u is the domain's vertex original[u] (empty: u), at vertices[u]:
  // the hierarchy's levels are sets of the domain's vertices.
  void compute(const SparseMatrix& A, const std::vector<Vec3>& vertices,
               Stored stored = Stored::kAll, const std::vector<int>& original = {});

  // Whether compute() on a system of n unknowns takes the multigrid, not CHOLMOD.
  bool iterative(std::size_t n) const;

  // Solves A x = b. On entry x is a warm start for CG (empty or zero means
  // none); CHOLMOD ignores it. Throws SolverError, naming the relative
  // residual, when CG does not reach its tolerance, a direct solve's residual
  // exceeds options.max_residual or the result is not finite.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  // z = an approximation of A^-1 r: one multigrid V-cycle, or CHOLMOD's exact
  // solve. Symmetric positive definite in r (a preconditioner).
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  const std::string& method_name() const { return method_; }  // "cholmod" or "cg+multigrid"
  int iterations() const { return iterations_; }  // of the last solve (0 for CHOLMOD)
  double residual() const { return residual_; }   // |A x - b| / |b| of the last solve
  double setup_seconds() const { return setup_seconds_; }  // of the last compute()
  int levels() const { return levels_; }  // multigrid levels of the last compute() (1: direct)

  // Frees what compute() built for the solves (the multigrid's levels: about
  // the memory of A), keeping what the next domains reuse (the hierarchy).
  void release();

  // Copies the above into stats (method, iterations, residual, setup seconds, levels).
  void report(SolverStats& stats) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int iterations_ = 0;
  double residual_ = 0;
  double setup_seconds_ = 0;
  int levels_ = 0;
  std::string method_ = "none";
};

}  // namespace pdd::detail
