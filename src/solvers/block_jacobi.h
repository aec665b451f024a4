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
  // joined transitively, strongest first, while a group has at most
  // max_block unknowns (coupling >= 1: plain Jacobi; max_block <= kMaxBlock).
  // A is symmetric, all its entries or its lower triangle stored.
  // Throws SolverError when a diagonal entry or a group's block is not
  // positive definite.
  // A in double or single precision (Scalar = double or float).
  template <class Scalar>
  BlockJacobi(const Eigen::SparseMatrix<Scalar>& A, double coupling, int max_block);

  // z = L^-1 r and z = L^-T r, D' = L L^T blockwise (Cholesky): L^-1 A L^-T has the
  // spectrum of D'^-1 A (for the smoother's bound). Before invert() only.
  void apply_inverse_factor(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  void apply_inverse_factor_transpose(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  // Turns each block's L^-1 into D'^-1 = L^-T L^-1 in place (one dense array, not two).
  void invert();
  // z = D'^-1 r, D' the block diagonal (z may not alias r). After invert() only.
  void apply_inverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  std::size_t num_blocks() const { return block_start_.empty() ? 0 : block_start_.size() - 1; }
  std::size_t blocked_unknowns() const { return block_unknown_.size(); }

 private:
  enum class Dense { kInverse, kFactor, kFactorTranspose };
  template <Dense kind>
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  Eigen::VectorXd inverse_diagonal_;  // 1 / a_ii off the groups, 0 on them
  std::vector<int> block_start_;      // group g: block_unknown_[block_start_[g], [g + 1])
  std::vector<int> block_unknown_;
  std::vector<std::size_t> matrix_start_;  // group g's dense m x m matrices at this offset
  std::vector<double> dense_;  // each block's L^-1, or its inverse after invert(); row-major
  bool inverted_ = false;
};

}  // namespace pdd::detail
