// Private to src/solvers: multigrid-preconditioned conjugate gradients.
//
// The levels are given as prolongations (the progressive hierarchy of
// hierarchy.h); the coarse operators are the Galerkin products P^T A P, held
// as lower triangles in single precision (they only precondition; CG's
// products are A's), the smoother is a Chebyshev polynomial in D^-1 A (D the
// diagonal of A with blocks for strongly coupled unknowns, block_jacobi.h),
// run on all cores, and the coarsest level is factored by CHOLMOD. Hand-written on
// Eigen and TBB: Debian's hypre is built without OpenMP, so in one process
// its BoomerAMG runs on one core, and on the SSD systems it needs 2-4x the
// iterations of this hierarchy (docs/benchmarks.md, "Multigrid").
#pragma once

#include <pdd/fem.h>
#include <pdd/solvers.h>

#include "common/parallel_kernels.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace pdd::detail {

// Set from LinearSolverOptions (include/pdd/solvers.h), whose defaults these are.
struct MultigridOptions {
  int smoothing_degree = LinearSolverOptions().smoothing_degree;  // Chebyshev polynomial degree,
                      // before and after the coarse correction, on the coarse levels
  int finest_smoothing_degree = LinearSolverOptions().finest_smoothing_degree;  // on the finest
  std::size_t coarsest_size = LinearSolverOptions().coarsest_size;  // levels this small are
                                                                    // solved directly
  double block_coupling = LinearSolverOptions().block_coupling;  // block_jacobi.h; 1: Jacobi
  int max_block = 16;  // the smoother's groups hold at most this many unknowns
};

class Multigrid {
 public:
  Multigrid();
  ~Multigrid();
  Multigrid(Multigrid&&) noexcept;
  Multigrid& operator=(Multigrid&&) noexcept;

  // The hierarchy for A (all entries stored, or its lower triangle; its
  // product's buffers are shared with the caller's, one product at a time):
  // prolongations[l] maps level l + 1 to level l (level 0 is A's,
  // prolongations[l].rows() = size of level l). A and the prolongations must
  // outlive the solves. Throws SolverError when the coarsest level is not
  // positive definite.
  void setup(const SymmetricProduct<double>& A, const std::vector<SparseMatrix>& prolongations,
             const MultigridOptions& options = {});

  // z = M^-1 r, one V-cycle from zero: symmetric positive definite in r.
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  // Frees the levels (setup() builds them again).
  void clear();

  std::size_t num_levels() const;
  std::size_t level_size(std::size_t level) const;
  std::size_t level_nonzeros(std::size_t level) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct CgResult {
  int iterations = 0;
  double residual = 0;  // |A x - b| / |b|, recomputed at the end
  bool converged = false;
};

// Preconditioned conjugate gradients from x (a warm start, or zero when x
// is empty) until |A x - b| <= tolerance |b| or max_iterations.
CgResult multigrid_cg(const SymmetricProduct<double>& A, const Multigrid& preconditioner,
                      const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                      int max_iterations);

}  // namespace pdd::detail
