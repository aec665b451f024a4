// The block accumulator of E(T)'s quadratic (energy_terms.h).
#include "optimize/energy_terms.h"

#include <algorithm>

namespace pdd::optimize_detail {

QuadraticAccumulator::QuadraticAccumulator(const Domain& domain) {
  const TetMesh& mesh = domain.mesh();
  const int n = static_cast<int>(mesh.vertices.size());
  stars_ = detail::vertex_stars(mesh);
  detail::OneRings rings = detail::one_rings(mesh, stars_);
  detail::poll();  // the run's cancellation
  offsets_.swap(rings.offsets);
  rows_.swap(rings.vertices);
  isotropic_.assign(rows_.size(), 0.0);
  coupled_index_.assign(rows_.size(), -1);
  b = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(n));
}

int QuadraticAccumulator::block(int i, int j) const {
  const auto first = rows_.begin() + offsets_[j], last = rows_.begin() + offsets_[j + 1];
  const auto it = std::lower_bound(first, last, i);
  if (it == last || *it != i) no_block();
  return static_cast<int>(it - rows_.begin());
}

void QuadraticAccumulator::no_block() {
  throw std::logic_error("optimizer: a term couples two vertices of no common tet");
}

void QuadraticAccumulator::add_coupled(int i, int j, const Eigen::Matrix3d& m) {
  int& index = coupled_index_[block(i, j)];
  if (index < 0) {
    index = static_cast<int>(coupled_.size());
    coupled_.push_back(Eigen::Matrix3d::Zero());
  }
  coupled_[index] += m;
}

Eigen::SparseMatrix<double> QuadraticAccumulator::matrix() const {
  const int n = static_cast<int>(offsets_.size()) - 1;
  // Column 3 j + k: for each block (i, j), rows 3 i .. 3 i + 2 when it has a
  // full part, row 3 i + k only otherwise.
  std::vector<int> column_size(n, 0);
  for (int j = 0; j < n; ++j)
    for (int s = offsets_[j]; s < offsets_[j + 1]; ++s)
      column_size[j] += coupled_index_[s] < 0 ? 1 : 3;
  detail::poll();  // the run's cancellation
  Eigen::SparseMatrix<double> A(3 * n, 3 * n);
  int* outer = A.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < 3; ++k) outer[3 * j + k + 1] = outer[3 * j + k] + column_size[j];
  A.resizeNonZeros(outer[3 * n]);
  int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  detail::polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int k = 0; k < 3; ++k) {
        int out = outer[3 * j + k];
        for (int s = offsets_[j]; s < offsets_[j + 1]; ++s) {
          const int i = rows_[s];
          if (coupled_index_[s] < 0) {
            inner[out] = 3 * i + k;
            values[out++] = isotropic_[s];
            continue;
          }
          const Eigen::Matrix3d& m = coupled_[coupled_index_[s]];
          for (int row = 0; row < 3; ++row) {
            inner[out] = 3 * i + row;
            values[out++] = m(row, k) + (row == k ? isotropic_[s] : 0.0);
          }
        }
      }
  });
  return A;
}

void QuadraticAccumulator::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = static_cast<int>(offsets_.size()) - 1;
  y.resize(3 * static_cast<Eigen::Index>(n));
  // y_j = sum over the blocks (i, j) of column j of A_ij^T x_i (A is symmetric).
  detail::polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int s = offsets_[j]; s < offsets_[j + 1]; ++s) {
        const Eigen::Vector3d xi = x.segment<3>(3 * static_cast<Eigen::Index>(rows_[s]));
        sum += isotropic_[s] * xi;
        if (coupled_index_[s] >= 0) sum.noalias() += coupled_[coupled_index_[s]].transpose() * xi;
      }
      y.segment<3>(3 * static_cast<Eigen::Index>(j)) = sum;
    }
  });
}

Eigen::Matrix3d QuadraticAccumulator::diagonal_block(int v) const {
  const int s = block(v, v);
  Eigen::Matrix3d d = isotropic_[s] * Eigen::Matrix3d::Identity();
  if (coupled_index_[s] >= 0) d += coupled_[coupled_index_[s]];
  return d;
}

}  // namespace pdd::optimize_detail
