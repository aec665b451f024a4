// Private to src/optimize: a block-Jacobi preconditioner for Eigen's
// ConjugateGradient, inverting the 3x3 diagonal block of each vertex. Eigen
// only ships the scalar Jacobi one, which is not invariant to rotations (the
// mid-edge term couples x, y and z through n n^T) and converges slowly where
// that term makes a vertex's block strongly anisotropic.
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <algorithm>
#include <vector>

namespace pdd::optimize_detail {

class BlockJacobiPreconditioner {
  using Vector = Eigen::VectorXd;

 public:
  using StorageIndex = Vector::StorageIndex;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  BlockJacobiPreconditioner() = default;

  Eigen::Index rows() const { return 3 * static_cast<Eigen::Index>(inverse_.size()); }
  Eigen::Index cols() const { return rows(); }

  template <typename MatType>
  BlockJacobiPreconditioner& analyzePattern(const MatType&) {
    return *this;
  }

  // The pseudo-inverse of each block, its small eigenvalues raised to 1e-12
  // of its largest (a vertex moved by one term only has a rank-deficient block).
  template <typename MatType>
  BlockJacobiPreconditioner& factorize(const MatType& mat) {
    const Eigen::Index blocks = mat.cols() / 3;
    std::vector<Eigen::Matrix3d> diagonal(blocks, Eigen::Matrix3d::Zero());
    for (Eigen::Index j = 0; j < mat.outerSize(); ++j)
      for (typename MatType::InnerIterator it(mat, j); it; ++it)
        if (it.row() / 3 == it.col() / 3) diagonal[j / 3](it.row() % 3, it.col() % 3) = it.value();
    inverse_.assign(blocks, Eigen::Matrix3d::Identity());
    for (Eigen::Index i = 0; i < blocks; ++i) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(diagonal[i]);
      const Eigen::Vector3d lambda = eigen.eigenvalues();
      const double largest = lambda.cwiseAbs().maxCoeff();
      if (!(largest > 0)) continue;
      const Eigen::Vector3d inverse = lambda.cwiseMax(1e-12 * largest).cwiseInverse();
      inverse_[i] = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
    }
    return *this;
  }

  template <typename MatType>
  BlockJacobiPreconditioner& compute(const MatType& mat) {
    return factorize(mat);
  }

  template <typename Rhs, typename Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    x.resize(b.rows());
    for (std::size_t i = 0; i < inverse_.size(); ++i)
      x.template segment<3>(3 * i) = inverse_[i] * b.template segment<3>(3 * i);
  }

  template <typename Rhs>
  const Eigen::Solve<BlockJacobiPreconditioner, Rhs> solve(const Eigen::MatrixBase<Rhs>& b) const {
    return Eigen::Solve<BlockJacobiPreconditioner, Rhs>(*this, b.derived());
  }

  Eigen::ComputationInfo info() { return Eigen::Success; }

 private:
  std::vector<Eigen::Matrix3d> inverse_;
};

}  // namespace pdd::optimize_detail
