// Private to src/: preconditioned conjugate gradients on the deterministic
// kernels of parallel_kernels.h, shared by the linear solves (multigrid
// preconditioner) and the optimizer (block-Jacobi, fixed vertices masked).
// Eigen's ConjugateGradient sums in an order that follows the thread count.
#pragma once

#include "common/cancellation.h"
#include "common/parallel_kernels.h"

#include <Eigen/Core>

#include <cmath>

namespace pdd::detail {

struct PcgResult {
  int iterations = 0;
  double residual = 0;  // |r| / reference at the end (the recursive residual)
  bool converged = false;
};

// CG from x with r = b - A x given (constraints already applied to it):
// apply(p, q) sets q = A p, precondition(r, z) sets z = M^-1 r, both
// symmetric positive definite on the unknowns. Stops once |r| <= tolerance x
// reference, after max_iterations, or when A p . p is not positive. Each
// iteration polls the run's cancellation (common/cancellation.h).
template <class Apply, class Precondition>
PcgResult preconditioned_cg(Apply apply, Precondition precondition, Eigen::VectorXd& r,
                            Eigen::VectorXd& x, double tolerance, double reference,
                            int max_iterations) {
  PcgResult result;
  const Eigen::Index n = x.size();
  result.residual = std::sqrt(deterministic_dot(r, r)) / reference;
  if (result.residual <= tolerance) {
    result.converged = true;
    return result;
  }
  Eigen::VectorXd z(n), p(n), q(n);
  precondition(r, z);
  p = z;
  double rz = deterministic_dot(r, z);
  for (int it = 1; it <= max_iterations; ++it) {
    poll();
    apply(p, q);
    const double pq = deterministic_dot(p, q);
    if (!(pq > 0)) break;  // A or M not positive definite numerically
    const double alpha = rz / pq;
    for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * q[i];
      }
    });
    result.iterations = it;
    result.residual = std::sqrt(deterministic_dot(r, r)) / reference;
    if (result.residual <= tolerance) {
      result.converged = true;
      break;
    }
    precondition(r, z);
    const double rz_next = deterministic_dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i) p[i] = z[i] + beta * p[i];
    });
  }
  return result;
}

}  // namespace pdd::detail
