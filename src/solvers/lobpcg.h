// Private to src/solvers: the largest eigenpair of A x = lambda B x (A
// symmetric positive semi-definite, B symmetric positive definite) by
// locally optimal preconditioned conjugate gradients [Knyazev 2001], with one
// vector. Hand-written: Spectra's LOBPCG takes its preconditioner as a sparse
// matrix, not as an operator such as a multigrid V-cycle, and Lanczos
// (Spectra's SymGEigsSolver) needs a full solve with B at every step.
#pragma once

#include <pdd/fem.h>

#include "common/parallel_kernels.h"

#include <Eigen/Core>
#include <functional>

namespace pdd::detail {

struct LobpcgResult {
  double eigenvalue = 0;
  int iterations = 0;
  double residual = 0;  // |A x - lambda B x| / (lambda |B x|), recomputed at the end
  bool converged = false;
};

// A and B are applied as SymmetricProduct (all entries stored or the lower
// triangle). x: on entry the start (any non-zero vector; a previous solution makes it
// fast), on exit the eigenvector, scaled to x^T B x = 1. precondition(r, z)
// sets z to an approximation of B^-1 r (one multigrid V-cycle, or an exact
// solve), symmetric positive definite in r. The start is first improved in
// span{x, 1}: a previous f differs from the new one mostly by a constant.
LobpcgResult largest_eigenpair(
    const SymmetricProduct<double>& A, const SymmetricProduct<double>& B,
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& precondition,
    Eigen::VectorXd& x, double tolerance, int max_iterations);

}  // namespace pdd::detail
