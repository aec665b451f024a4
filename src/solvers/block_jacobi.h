// Private to src/solvers: the preconditioner inside the multigrid's smoother.
// Jacobi (D = diag A), except on groups of strongly coupled unknowns, whose
// diagonal block of A is inverted whole. SSD's squared Hessian (Eq. 15) on a
// Delaunay domain couples some neighbours almost as strongly as each is tied
// to itself (|a_ij| close to sqrt(a_ii a_jj), around short edges and flat
// tets): their combinations with a small energy then have a large diagonal,
// a point smoother leaves them and no coarse level can represent them
// (docs/benchmarks.md, "Multigrid"). Solving each group's block removes them.
// Hand-written: neither Eigen nor hypre's smoothers form such blocks from
// the coupling strength.
#pragma once

#include <pdd/fem.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pdd::detail {

class BlockJacobi {
 public:
  static constexpr int kMaxBlock = 64;

  BlockJacobi() = default;
  // The groups: unknowns i and j with |a_ij| > coupling sqrt(a_ii a_jj),
  // joined transitively while a group has at most max_block unknowns
  // (coupling >= 1: plain Jacobi; max_block <= kMaxBlock). A is symmetric with all entries stored.
  // Throws SolverError when a diagonal entry or a group's block is not
  // positive definite.
  // A in double or single precision (Scalar = double or float).
  template <class Scalar>
  BlockJacobi(const Eigen::SparseMatrix<Scalar>& A, double coupling, int max_block);

  // z = D'^-1 r, D' the block diagonal (z may not alias r).
  void apply_inverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  // z = D'^-1/2 r, the symmetric square root (for the smoother's bound).
  void apply_inverse_sqrt(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  std::size_t num_blocks() const { return block_start_.empty() ? 0 : block_start_.size() - 1; }
  std::size_t blocked_unknowns() const { return block_unknown_.size(); }

 private:
  template <bool kSqrt>
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  Eigen::VectorXd inverse_diagonal_;  // 1 / a_ii off the groups, 0 on them
  std::vector<int> block_start_;      // group g: block_unknown_[block_start_[g], [g + 1])
  std::vector<int> block_unknown_;
  std::vector<std::size_t> matrix_start_;  // group g's dense m x m matrices at this offset
  std::vector<double> inverse_;            // the blocks' inverses, row-major
  std::vector<double> inverse_sqrt_;       // and their symmetric inverse square roots
};

}  // namespace pdd::detail
